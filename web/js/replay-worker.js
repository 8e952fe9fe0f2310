/**
 * Web Worker of a replay: holds one recording (player.js) and decodes the frames asked for, off
 * the page's thread. Start it as a module worker.
 *
 * Messages in:
 * - `{ open: ArrayBuffer }` (transfer it): replies `{ opened: { frames, times, bounds, spacing } }`
 *   (times in s; bounds `{min, max}` from the positions' quantisation range, the scene's domain;
 *   spacing estimated from frame 0, m), then frame 0 as below (`id` null), then
 *   `{ progress: fraction }` while every frame is decoded once to index the file, then
 *   `{ ready: { extent, indexMs } }` (`{min, max}`, m: the box every frame's particles lie in;
 *   the time indexing took); or
 *   `{ error: message }` for a file that is not a whole recording.
 * - `{ seek: k, id }`: replies `{ id, index: k, frame, decodeMs }` (`decodeMs`: the whole seek,
 *   frames decoded on the way included), the frame's arrays transferred, or `{ id, error: message }`.
 * @module
 */

import { Player } from './player.js';
import { estimateSpacing } from './spacing.js';

/** The replies to one message, posted through `post(message, transfer)`. */
export function handle(state, data, post) {
  const now = () => performance.now();
  if (data?.open) {
    try {
      const player = new Player(new Uint8Array(data.open));
      state.player = player;
      const t0 = now();
      const first = player.frame(0);
      const decodeMs = now() - t0;
      const ranges = first.header.channels[0].ranges;
      post({
        opened: {
          frames: player.length, times: player.times,
          bounds: { min: ranges.map((r) => r.min), max: ranges.map((r) => r.max) },
          spacing: estimateSpacing(first.positions),
        },
      });
      post(...frameMessage(null, 0, first, decodeMs));
      const t1 = now();
      player.prepare((done, total) => { if (done % 10 === 0 || done === total) post({ progress: done / total }); });
      post({ ready: { extent: player.extent, indexMs: now() - t1 } });
    } catch (e) {
      state.player = null;
      post({ error: e.message });
    }
    return;
  }
  if (data?.seek !== undefined) {
    try {
      if (!state.player) throw new Error('no recording is open');
      const t0 = now();
      const frame = state.player.frame(data.seek);
      post(...frameMessage(data.id, data.seek, frame, now() - t0));
    } catch (e) {
      post({ id: data.id, error: e.message });
    }
  }
}

/** A decoded frame as a message and the buffers to transfer with it. */
function frameMessage(id, index, frame, decodeMs) {
  const transfer = [frame.positions.buffer, ...frame.channels.map((c) => c.values.buffer)];
  return [{ id, index, frame, decodeMs }, transfer];
}

const scope = typeof self === 'object' && self !== null ? self : null;
if (scope !== null && typeof scope.postMessage === 'function' && typeof scope.document === 'undefined') {
  const state = { player: null };
  scope.onmessage = (event) => handle(state, event.data, (message, transfer = []) => scope.postMessage(message, transfer));
}
