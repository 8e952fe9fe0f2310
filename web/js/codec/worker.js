/**
 * Web Worker entry: decodes frames off the main thread with one persistent {@link Decoder}
 * (so identity-ordered delta frames apply to the frames before them).
 *
 * Start it as a module worker: `new Worker(new URL('./worker.js', import.meta.url), { type: 'module' })`.
 *
 * Messages in (an optional `id` is echoed back in the reply):
 * - `{ bytes: ArrayBuffer }` (transfer it): decode one frame. Reply: `{ id, header, positions,
 *   grid?, channels, decodeMs }` (see the decoder's `Frame`), the arrays' buffers transferred; or `{ id, error: { kind, name, message, ...fields } }` where `kind` is
 *   the `DecodeError` variant (`'Incomplete'`, `'Malformed'`, `'UnsupportedVersion'`,
 *   `'NeedKeyframe'`, `'TooLarge'`), `'TypeError'` for a message without bytes, or `'Internal'`.
 * - `{ limits: { maxParticles, maxFrameBytes } }`: a fresh decoder with these limits. Reply `{ id, ok: true }`.
 * - `{ reset: true }`: forget the held frame (only a keyframe decodes next). Reply `{ id, ok: true }`.
 *
 * Header fields `sceneId`, `sequence`, `baseSequence` and `step` are BigInts (structured clone
 * carries them).
 * @module
 */

import { Decoder } from './decoder.js';
import { DecodeError } from './errors.js';

const now = () => (typeof performance !== 'undefined' ? performance.now() : Date.now());

/**
 * The message handler, apart from the worker plumbing (so it can be tested anywhere).
 * @param {{decoder: Decoder}} state holds the persistent decoder
 * @param {any} data the message received
 * @returns {{message: object, transfer: ArrayBuffer[]}} the reply and what to transfer with it
 */
export function handleMessage(state, data) {
  const id = data !== null && typeof data === 'object' ? data.id : undefined;
  try {
    if (data?.limits) {
      state.decoder = new Decoder(data.limits);
      return { message: { id, ok: true }, transfer: [] };
    }
    if (data?.reset) {
      state.decoder.reset();
      return { message: { id, ok: true }, transfer: [] };
    }
    const bytes = data?.bytes;
    if (!(bytes instanceof ArrayBuffer) && !ArrayBuffer.isView(bytes)) {
      return { message: { id, error: { kind: 'TypeError', message: 'expected { bytes: ArrayBuffer }' } }, transfer: [] };
    }
    const t0 = now();
    const frame = state.decoder.decode(bytes);
    const decodeMs = now() - t0;
    const message = { id, ...frame, decodeMs };
    const transfer = [frame.positions.buffer, ...frame.channels.map((c) => c.values.buffer)];
    return { message, transfer };
  } catch (e) {
    const error = e instanceof DecodeError ? e.toJSON() : { kind: 'Internal', message: String(e?.message ?? e) };
    return { message: { id, error }, transfer: [] };
  }
}

// Attach to the worker scope when running as a worker (not when imported on a page or in a test).
const scope = typeof self === 'object' && self !== null ? self : null;
if (scope !== null && typeof scope.postMessage === 'function' && typeof scope.document === 'undefined') {
  const state = { decoder: new Decoder() };
  scope.onmessage = (event) => {
    const { message, transfer } = handleMessage(state, event.data);
    scope.postMessage(message, transfer);
  };
}
