/**
 * The frame decoder (mirrors `proto/src/decoder.rs`): checks a frame completely before
 * trusting it, and keeps the last identity-ordered frame's codes to apply delta frames to.
 * @module
 */

import { MalformedError, NeedKeyframeError } from './errors.js';
import { CHANNELS, ChannelKind, DEFAULT_LIMITS, Mode, readHeader } from './header.js';
import { Predictor, readCodes, readGains } from './predict.js';
import { dequantiseInto, sameQuantizer } from './quantize.js';
import { Reader } from './reader.js';
import { Scratch, readStream } from './stream.js';
import { readMortonPositions } from './unordered.js';

/**
 * @typedef {object} Channel
 * @property {number} tag the channel's tag
 * @property {string} name its name in the channel table, or `channel <tag>` for a per-scene
 *   channel (whose name the scene's info gives)
 * @property {number} components values per particle
 * @property {Float32Array|Uint8Array} values `components * n` values, interleaved; a
 *   `Uint8Array` for exact channels (material indices)
 */

/**
 * @typedef {object} Frame
 * @property {import('./header.js').Header} header the header and channel table
 * @property {Float32Array} positions `3 n` values (m), x, y, z interleaved (empty in a grid frame)
 * @property {{origin: number[], size: number[], dims: number[]}} [grid] a grid frame's grid (m,
 *   cells per axis; cells x fastest)
 * @property {Channel[]} channels the other channels, in the frame's order
 * @property {Uint32Array} [ids] the particles' stable ids, ascending, where the frame carries
 *   them (identity-ordered frames of a set whose particles are born and die, version 5)
 */

/**
 * Bytes of `input` as a `Uint8Array` view (no copy).
 * @param {ArrayBuffer|ArrayBufferView} input
 * @returns {Uint8Array}
 */
function bytesOf(input) {
  if (input instanceof Uint8Array) return input;
  if (input instanceof ArrayBuffer) return new Uint8Array(input);
  if (ArrayBuffer.isView(input)) return new Uint8Array(input.buffer, input.byteOffset, input.byteLength);
  if (typeof SharedArrayBuffer !== 'undefined' && input instanceof SharedArrayBuffer) return new Uint8Array(input);
  throw new TypeError('Decoder.decode expects an ArrayBuffer or a Uint8Array');
}

/** Whether the held channel `held` was quantised exactly as `info` says (Rust `same_quantisation`). */
function sameQuantisation(held, info) {
  return (
    held.tag === info.tag &&
    held.ranges.length === info.ranges.length &&
    held.ranges.every((r, k) => sameQuantizer(r, held.bits, info.ranges[k], info.bits))
  );
}

/**
 * Decodes a stream of frames from one encoder. Like Rust's `Decoder`: every frame is checked
 * against the caller's limits before anything is allocated for it, any invalid input throws a
 * {@link import('./errors.js').DecodeError} subclass, and a refused frame leaves the state as
 * it was.
 */
export class Decoder {
  #limits;
  /** @type {bigint|null} */
  #lastSequence = null;
  /** @type {{sceneId: bigint, sequence: bigint, channels: object[], before: Uint16Array[]|null}|null} */
  #base = null;
  #scratch = new Scratch();

  /**
   * @param {{maxParticles?: number, maxFrameBytes?: number}} [limits] most particles and bytes
   *   per frame (default 16 Mi particles and 1 GiB, as Rust's `Limits::default()`)
   */
  constructor(limits = {}) {
    this.#limits = Object.freeze({ ...DEFAULT_LIMITS, ...limits });
  }

  /** @returns {{maxParticles: number, maxFrameBytes: number}} the limits in force */
  get limits() {
    return this.#limits;
  }

  /** @returns {bigint|null} sequence number of the last frame decoded, of either mode */
  get lastSequence() {
    return this.#lastSequence;
  }

  /** @returns {bigint|null} sequence number of the identity-ordered frame delta frames can apply to */
  get heldSequence() {
    return this.#base === null ? null : this.#base.sequence;
  }

  /** Forgets the held frame, so only a keyframe decodes next. */
  reset() {
    this.#base = null;
    this.#lastSequence = null;
  }

  /**
   * The decoder's state after the last frame, to come back to with {@link restore} (a replay
   * seeks near a frame this way instead of decoding from its keyframe). Cheap: the held codes
   * are never changed in place, so the state shares them.
   * @returns {object} opaque
   */
  checkpoint() {
    return { base: this.#base, lastSequence: this.#lastSequence };
  }

  /**
   * Goes back to a state from {@link checkpoint}: the next delta frame applies to the frame
   * decoded before it was taken.
   * @param {object} state
   */
  restore(state) {
    this.#base = state.base;
    this.#lastSequence = state.lastSequence;
  }

  /**
   * Decodes the frame at the start of `input` (bytes after its frame length are not read).
   * The u64 header fields `sceneId`, `sequence`, `baseSequence` and `step` are BigInts (they
   * may exceed 2^53); `time` and the counts and lengths (u32) are numbers.
   * @param {ArrayBuffer|Uint8Array|ArrayBufferView} input
   * @returns {Frame}
   * @throws {import('./errors.js').DecodeError} IncompleteError, MalformedError,
   *   UnsupportedVersionError, NeedKeyframeError or TooLargeError
   */
  decode(input) {
    const bytes = bytesOf(input);
    const header = readHeader(bytes, this.#limits);
    const frame = bytes.subarray(0, header.frameLen);
    const n = header.particleCount;
    const identity = header.modeTag === Mode.IDENTITY_ORDERED;
    let base = null;
    if (identity && !header.keyframe) {
      const held = this.#base;
      if (held === null || held.sequence !== header.baseSequence || held.sceneId !== header.sceneId) {
        throw new NeedKeyframeError(header.sequence, header.baseSequence, held === null ? null : held.sequence);
      }
      base = held;
    }
    const r = new Reader(frame, 'channel payloads');
    r.skip(header.headerLen);
    const out = { header, positions: new Float32Array(0), channels: [] };
    const kept = [];
    header.channels.forEach((info, i) => {
      const payload = r.take(info.payloadLen);
      const p = new Reader(payload, 'channel payload');
      const inChannel = (e) =>
        e instanceof MalformedError ? new MalformedError(`channel ${i} (${info.kind}): ${e.what}`) : e;
      if (info.tag === ChannelKind.GRID) {
        const dims = [p.u32(), p.u32(), p.u32()];
        if (dims[0] * dims[1] * dims[2] !== n) {
          throw inChannel(new MalformedError(`cell counts [${dims.join(', ')}] do not make the frame's ${n} cells`));
        }
        const rg = info.ranges;
        out.grid = {
          origin: rg.map((x) => x.min), size: rg.map((x) => Math.fround(x.max - x.min)), dims,
        };
      } else if (info.tag === ChannelKind.IDS) {
        try {
          out.ids = readIds(p, n, this.#scratch);
        } catch (e) {
          throw inChannel(e);
        }
      } else if (info.predictorTag === Predictor.MORTON) {
        try {
          out.positions = readMortonPositions(p, n, info.ranges, info.bits, this.#scratch);
        } catch (e) {
          throw inChannel(e);
        }
      } else {
        const [prev, before] = references(header, info, i, base);
        const codes = [];
        try {
          const linear = info.predictorTag === Predictor.LINEAR;
          const gains = linear ? readGains(p, info.ranges.length) : [];
          for (let k = 0; k < info.ranges.length; k++) {
            const refK = prev !== null && k < prev.codes.length ? prev.codes[k] : null;
            const beforeK = before !== null && k < before.length ? before[k] : null;
            const gain = linear ? gains[k] : 0;
            codes.push(readCodes(p, n, info.bits, info.predictorTag, refK, beforeK, gain, this.#scratch));
          }
        } catch (e) {
          throw inChannel(e);
        }
        store(out, info, codes, n);
        if (identity) kept.push({ tag: info.tag, bits: info.bits, ranges: info.ranges, codes });
      }
      if (p.remaining() !== 0) throw inChannel(new MalformedError(`${p.remaining()} bytes left over`));
    });
    // A delta frame's particles are its base frame's.
    if (base !== null && !sameIds(base.ids, out.ids)) {
      throw new MalformedError(
        `delta frame ${header.sequence} carries other particle ids than its base frame ${header.baseSequence}`);
    }
    if (identity) {
      const before = base !== null && base.channels.length > 0 ? base.channels[0].codes : null;
      this.#base = { sceneId: header.sceneId, sequence: header.sequence, channels: kept, before, ids: out.ids ?? null };
    }
    this.#lastSequence = header.sequence;
    return out;
  }
}

/**
 * The ids channel's payload of `n` particles (predictor gaps, Rust `read_ids`): the first id,
 * then each minus the one before it minus one, in one stream of at most 32 bits.
 * @returns {Uint32Array} ascending ids
 */
function readIds(r, n, scratch) {
  const gaps = readStream(r, n, 32, scratch);
  const ids = new Uint32Array(n);
  let next = 0;
  for (let k = 0; k < n; k++) {
    const id = next + gaps[k];
    if (id > 0xffffffff) throw new MalformedError(`id ${k} is ${id}, beyond 32 bits`);
    ids[k] = id;
    next = id + 1;
  }
  return ids;
}

/** Whether two frames carry the same ids (or neither carries any). */
function sameIds(a, b) {
  if (a === null || a === undefined || b === null || b === undefined) return (a ?? null) === (b ?? null);
  return a.length === b.length && a.every((x, k) => x === b[k]);
}

/**
 * The base frame's codes of this channel and, for positions, of the frame before the base;
 * refuses temporal predictors the held frames cannot serve (Rust `Decoder::decode`).
 */
function references(header, info, i, base) {
  const prev = base === null ? null : (base.channels.find((c) => c.tag === info.tag) ?? null);
  const before = base !== null && info.tag === ChannelKind.POSITION ? base.before : null;
  const temporal = info.predictorTag === Predictor.BASE || info.predictorTag === Predictor.LINEAR;
  if (temporal && !(prev !== null && sameQuantisation(prev, info))) {
    throw new MalformedError(
      `channel ${i} (${info.kind}) predicts from frame ${header.baseSequence}, which quantised it differently or lacks it`,
    );
  }
  if (info.predictorTag === Predictor.LINEAR && before === null) {
    throw new MalformedError(
      `channel ${i} (${info.kind}) extrapolates from frame ${header.baseSequence} and the one before, but that was a keyframe`,
    );
  }
  return [prev, before];
}

/** De-quantises a channel's codes into positions or a channel of the frame (Rust `codes::values`). */
function store(out, info, codes, n) {
  if (CHANNELS[info.tag]?.exact) {
    out.channels.push({ tag: info.tag, name: info.kind, components: 1, values: Uint8Array.from(codes[0]) });
    return;
  }
  const c = codes.length;
  const values = new Float32Array(c * n);
  for (let k = 0; k < c; k++) dequantiseInto(codes[k], info.ranges[k], info.bits, values, k, c);
  if (info.tag === ChannelKind.POSITION) out.positions = values;
  else out.channels.push({ tag: info.tag, name: info.kind, components: c, values });
}
