/**
 * The frame header and channel table (mirrors `proto/src/header.rs` and `read_header` /
 * `check` in `proto/src/decoder.rs`). Little-endian throughout.
 *
 * Fixed header (64 bytes): magic `FLOF` (0), version u16 (4), mode u8 (6), flags u8 (7, bit 0
 * keyframe), frame length u32 (8), particle count u32 (12), scene id u64 (16), sequence u64
 * (24), base sequence u64 (32), step u64 (40), time f64 (48), channel count u8 (56, 1 to 16),
 * particle set u8 (57; version 4, zero in version 3), 6 reserved zero bytes (58). Then per
 * channel (`8 + 12 c` bytes): kind tag u8 (`proto/channels.json`, copied in `channels.js`),
 * components u8 (1 to 4), bits u8 (1 to 16), predictor u8, payload length u32, and per
 * component range min f32, max f32, max error f32.
 * @module
 */

import { IncompleteError, MalformedError, TooLargeError, UnsupportedVersionError } from './errors.js';
import { PREDICTOR_DEBUG_NAMES, PREDICTOR_NAMES, Predictor } from './predict.js';
import { RangeForm, checkRange } from './quantize.js';
import { TABLE } from './channels.js';
import { Reader } from './reader.js';

/** The first four bytes of every frame. */
export const MAGIC = 'FLOF';
const MAGIC_BYTES = [0x46, 0x4c, 0x4f, 0x46];
/** The newest format version this decoder reads. */
export const VERSION = 5;
/** The oldest format version this decoder reads. */
export const MIN_VERSION = 3;
/** Bytes of the fixed header. */
export const FIXED_HEADER_LEN = 64;
/** Most channels a frame may declare. */
export const MAX_CHANNELS = 16;
/** Most components a channel may have. */
export const MAX_COMPONENTS = 4;

/** Mode tags. */
export const Mode = Object.freeze({ UNORDERED: 0, IDENTITY_ORDERED: 1, GRID: 2 });
const MODE_NAMES = ['unordered', 'identity_ordered', 'grid'];
/** Rust `Debug` names of the modes, for messages. */
const MODE_DEBUG = ['Unordered', 'IdentityOrdered', 'Grid'];

/** The channel table's rows, by tag. */
export const CHANNELS = Object.freeze(TABLE.channels.map((c) => Object.freeze({ ...c })));
/** Tags of the table's channels, by upper-case name (`ChannelKind.VELOCITY`). */
export const ChannelKind = Object.freeze(Object.fromEntries(CHANNELS.map((c) => [c.name.toUpperCase(), c.tag])));
/** The table's name of `tag`, or `channel <tag>` for a tag it lacks (a per-scene channel). */
export const kindName = (tag) => CHANNELS[tag]?.name ?? `channel ${tag}`;

/**
 * Default limits, as Rust's `Limits::default()`: 16 Mi particles and 1 GiB per frame.
 * @type {{maxParticles: number, maxFrameBytes: number}}
 */
export const DEFAULT_LIMITS = Object.freeze({ maxParticles: 1 << 24, maxFrameBytes: 2 ** 30 });

/**
 * @typedef {object} ChannelInfo
 * @property {number} tag kind tag
 * @property {string} kind kind name (`'position'`, ...), or `'channel <tag>'` for a tag the table lacks
 * @property {number} components components per particle
 * @property {number} bits quantisation bits per component
 * @property {number} predictorTag predictor tag (see `Predictor`)
 * @property {string} predictor predictor name (`'none'`, `'previous'`, `'base'`, `'morton'`, `'linear'`)
 * @property {number} payloadLen bytes of the channel's payload
 * @property {{min: number, max: number, maxError: number}[]} ranges per component: range and the
 *   largest quantisation error it implies (half a step; 0 for phase), all f32 values
 */

/**
 * @typedef {object} Header
 * @property {string} magic always `'FLOF'`
 * @property {number} version format version
 * @property {string} mode `'unordered'`, `'identity_ordered'` or `'grid'`
 * @property {number} modeTag 0, 1 or 2
 * @property {number} set which of the scene's particle sets (or grids) the frame carries
 * @property {boolean} keyframe whether the frame decodes on its own
 * @property {number} frameLen bytes of the whole frame
 * @property {number} particleCount particles in the frame
 * @property {bigint} sceneId u64, a BigInt (may exceed 2^53)
 * @property {bigint} sequence u64, a BigInt: the frame's place in its encoder's stream
 * @property {bigint} baseSequence u64, a BigInt: the frame a delta frame predicts from (else `sequence`)
 * @property {bigint} step u64, a BigInt: the simulation step
 * @property {number} time simulated time (s)
 * @property {number} headerLen bytes of the fixed header and channel table
 * @property {ChannelInfo[]} channels positions (or the grid) first
 */

/**
 * Reads and checks the header of the frame at the start of `bytes` without decoding its
 * payload, exactly as Rust's `read_header`: to learn a frame's length, or split a byte stream.
 * @param {Uint8Array} bytes
 * @param {{maxParticles: number, maxFrameBytes: number}} [limits=DEFAULT_LIMITS]
 * @returns {Header}
 * @throws {import('./errors.js').DecodeError} Incomplete, Malformed, UnsupportedVersion or TooLarge
 */
export function readHeader(bytes, limits = DEFAULT_LIMITS) {
  const available = bytes.length;
  const prefix = Math.min(available, 4);
  for (let i = 0; i < prefix; i++) {
    if (bytes[i] !== MAGIC_BYTES[i]) throw new MalformedError('not a Floe frame (bad magic)');
  }
  if (available >= 6) {
    const found = bytes[4] | (bytes[5] << 8);
    if (found < MIN_VERSION || found > VERSION) throw new UnsupportedVersionError(found, MIN_VERSION, VERSION);
  }
  if (available < FIXED_HEADER_LEN) throw new IncompleteError(FIXED_HEADER_LEN, available);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const frameLen = view.getUint32(8, true);
  const particles = view.getUint32(12, true);
  if (frameLen > limits.maxFrameBytes) throw new TooLargeError('bytes', frameLen, limits.maxFrameBytes);
  if (particles > limits.maxParticles) throw new TooLargeError('particles', particles, limits.maxParticles);
  if (frameLen < FIXED_HEADER_LEN) {
    throw new MalformedError(`frame length ${frameLen} is shorter than the fixed header`);
  }
  if (available < frameLen) throw new IncompleteError(frameLen, available);
  const header = parse(bytes.subarray(0, frameLen));
  check(header);
  return header;
}

/** Reads the fields of a frame of exactly `frame.length` bytes, each checked on its own. */
function parse(frame) {
  const r = new Reader(frame, 'header');
  r.skip(4);
  const version = r.u16();
  const modeTag = r.u8();
  if (modeTag > 2) throw new MalformedError(`unknown mode ${modeTag}`);
  const flags = r.u8();
  if ((flags & ~1) !== 0) {
    throw new MalformedError(`reserved flag bits set: 0x${flags.toString(16).padStart(2, '0')}`);
  }
  const frameLen = r.u32();
  const particleCount = r.u32();
  const sceneId = r.u64();
  const sequence = r.u64();
  const baseSequence = r.u64();
  const step = r.u64();
  const time = r.f64();
  if (!Number.isFinite(time)) throw new MalformedError(`time is ${Number.isNaN(time) ? 'NaN' : time > 0 ? 'inf' : '-inf'}`);
  const count = r.u8();
  if (count < 1 || count > MAX_CHANNELS) {
    throw new MalformedError(`${count} channels (1 to ${MAX_CHANNELS} allowed)`);
  }
  const set = r.u8();
  if (r.take(6).some((b) => b !== 0) || (version < 4 && set !== 0)) {
    throw new MalformedError('reserved header bytes are not zero');
  }
  const channels = [];
  for (let i = 0; i < count; i++) channels.push(readChannel(r, i));
  return {
    magic: MAGIC, version, mode: MODE_NAMES[modeTag], modeTag, keyframe: (flags & 1) !== 0,
    frameLen, particleCount, sceneId, set, sequence, baseSequence, step, time, headerLen: r.pos, channels,
  };
}

function readChannel(r, index) {
  const bad = (what) => new MalformedError(`channel ${index}: ${what}`);
  const tag = r.u8();
  const components = r.u8();
  const bits = r.u8();
  const predictorTag = r.u8();
  if (components < 1 || components > MAX_COMPONENTS) {
    throw bad(`${components} components (1 to ${MAX_COMPONENTS} allowed)`);
  }
  if (bits < 1 || bits > 16) throw bad(`${bits} quantisation bits (1 to 16 allowed)`);
  if (predictorTag > 5) throw bad(`unknown predictor ${predictorTag}`);
  const payloadLen = r.u32();
  const ranges = [];
  for (let k = 0; k < components; k++) {
    const range = { min: r.f32(), max: r.f32(), maxError: r.f32() };
    const extent = tag === ChannelKind.GRID || tag === ChannelKind.IDS;
    const form = extent ? RangeForm.EXTENT : CHANNELS[tag]?.exact ? RangeForm.EXACT_U8 : RangeForm.QUANTISED;
    const what = checkRange(range, bits, form);
    if (what !== null) throw bad(`component ${k}: ${what}`);
    ranges.push(range);
  }
  return {
    tag, kind: kindName(tag), components, bits,
    predictorTag, predictor: PREDICTOR_NAMES[predictorTag], payloadLen, ranges,
  };
}

/** Predictors allowed by mode, kind and keyframe flag (Rust `check`). */
function allowed(modeTag, tag, delta) {
  if (tag === ChannelKind.IDS) return [Predictor.GAPS];
  if (modeTag === Mode.GRID) return tag === ChannelKind.GRID ? [Predictor.NONE] : [Predictor.NONE, Predictor.PREVIOUS];
  const isPosition = tag === ChannelKind.POSITION;
  if (modeTag === Mode.UNORDERED) return isPosition ? [Predictor.MORTON] : [Predictor.NONE, Predictor.PREVIOUS];
  if (!delta) return [Predictor.NONE, Predictor.PREVIOUS];
  return isPosition ? [Predictor.BASE, Predictor.LINEAR] : [Predictor.NONE, Predictor.PREVIOUS, Predictor.BASE];
}

/** Checks how the header's fields fit together (Rust `check` in `decoder.rs`). */
function check(h) {
  const delta = h.modeTag === Mode.IDENTITY_ORDERED && !h.keyframe;
  if (h.modeTag !== Mode.IDENTITY_ORDERED && !h.keyframe) {
    throw new MalformedError('unordered and grid frames are all keyframes');
  }
  if (h.modeTag === Mode.GRID && h.version < 4) {
    throw new MalformedError(`grid frames need format version 4, not ${h.version}`);
  }
  const ids = h.channels.findIndex((c) => c.tag === ChannelKind.IDS);
  if (ids >= 0 && (h.version < 5 || h.modeTag !== Mode.IDENTITY_ORDERED || ids + 1 !== h.channels.length)) {
    throw new MalformedError(`channel ${ids}: ids come last, in identity-ordered frames of version 5 (this one: ${MODE_DEBUG[h.modeTag]}, version ${h.version})`);
  }
  if (!delta && h.baseSequence !== h.sequence) {
    throw new MalformedError(`keyframe ${h.sequence} names base frame ${h.baseSequence}`);
  }
  if (delta && h.baseSequence === h.sequence) throw new MalformedError(`delta frame ${h.sequence} predicts from itself`);
  const first = h.modeTag === Mode.GRID ? ChannelKind.GRID : ChannelKind.POSITION;
  const seen = new Set();
  let total = h.headerLen;
  h.channels.forEach((c, i) => {
    total += c.payloadLen;
    const leading = c.tag === ChannelKind.POSITION || c.tag === ChannelKind.GRID;
    if ((i === 0) !== (c.tag === first) || (i > 0 && leading)) {
      throw new MalformedError(`channel ${i} is ${c.kind}; ${kindName(first)} comes first and once`);
    }
    if (seen.has(c.tag)) throw new MalformedError(`channel ${i}: a second ${c.kind} channel`);
    seen.add(c.tag);
    const def = CHANNELS[c.tag];
    if (def !== undefined && c.components !== def.components) {
      throw new MalformedError(`channel ${i}: ${c.kind} has ${def.components} components, not ${c.components}`);
    }
    if (c.tag === ChannelKind.GRID && (c.payloadLen !== 12 || c.bits !== 16)) {
      throw new MalformedError(`channel ${i}: the grid has 16 bits and 12 bytes, not ${c.bits} and ${c.payloadLen}`);
    }
    if (!allowed(h.modeTag, c.tag, delta).includes(c.predictorTag)) {
      throw new MalformedError(`channel ${i}: predictor ${PREDICTOR_DEBUG_NAMES[c.predictorTag]} is not allowed for ${c.kind} in this frame`);
    }
  });
  if (total !== h.frameLen) {
    throw new MalformedError(`header and payloads add up to ${total} bytes, but the frame length is ${h.frameLen}`);
  }
}
