/**
 * Streams: how a channel's payload stores `n` unsigned values, Rice-coded in blocks
 * (mirrors `proto/src/stream.rs`, where the layout is documented in full).
 *
 * | offset | size | field |
 * |---:|---:|---|
 * | 0 | 1 | width `w`: bits of the largest value |
 * | 1 | 4 | length `len` of the coded blocks in bytes (u32) |
 * | 5 | len | blocks of 128 values, bits packed from the least significant bit of each byte up |
 *
 * A block starts with a 6-bit parameter `k` (63: all values 0, nothing more stored); each
 * value is then `q = v >> k` below 16 as `q` zero bits, a one bit and the low `k` bits of
 * `v`, or 16 zero bits and `v` in `w` bits. `len` is exactly the bytes the bits need, and the
 * bits after the last value are zero.
 * @module
 */

import { MalformedError } from './errors.js';

/** Values per block. */
export const BLOCK = 128;
/** Block parameter meaning "every value of the block is 0". */
export const ZERO_BLOCK = 63;
/** Quotients from this on are escaped (the value stored in `w` bits). */
export const ESCAPE = 16;
const PARAMETER_BITS = 6;
const TWO_24 = 16777216;

/** Scratch buffers a decoder reuses from frame to frame. */
export class Scratch {
  constructor() {
    /** @type {Float64Array} */
    this.values = new Float64Array(0);
  }

  /**
   * A buffer of at least `n` values (grown, never shrunk).
   * @param {number} n
   * @returns {Float64Array}
   */
  valuesOf(n) {
    if (this.values.length < n) this.values = new Float64Array(Math.max(n, this.values.length * 2));
    return this.values;
  }
}

/**
 * The 25 or more bits from bit `pos` up (bytes past the end read as zero).
 * @param {Uint8Array} bytes @param {number} pos
 * @returns {number}
 */
function peek(bytes, pos) {
  const at = pos >>> 3;
  const word = at + 3 < bytes.length
    ? bytes[at] | (bytes[at + 1] << 8) | (bytes[at + 2] << 16) | (bytes[at + 3] << 24)
    : (bytes[at] ?? 0) | ((bytes[at + 1] ?? 0) << 8) | ((bytes[at + 2] ?? 0) << 16);
  return word >>> (pos & 7);
}

/**
 * `count` bits (up to 48) from bit `pos`, as a number.
 * @param {Uint8Array} bytes @param {number} pos @param {number} count
 * @returns {number}
 */
function bitsAt(bytes, pos, count) {
  if (count <= 24) return peek(bytes, pos) & ((1 << count) - 1);
  const lo = peek(bytes, pos) & 0xffffff;
  return (peek(bytes, pos + 24) & ((1 << (count - 24)) - 1)) * TWO_24 + lo;
}

/**
 * Reads a stream of `n` values of at most `maxWidth` bits (up to 48) from `r` into
 * `scratch.values` (the first `n` entries).
 *
 * Allocation is bounded by `n` (checked by the caller against its limit) and by the bytes
 * present: every block takes at least 6 bits, so a stream too short for `n` values is refused
 * before anything is allocated.
 * @param {import('./reader.js').Reader} r the channel payload
 * @param {number} n values
 * @param {number} maxWidth most bits per value allowed
 * @param {Scratch} scratch
 * @returns {Float64Array} `scratch.values`
 * @throws {MalformedError}
 */
export function readStream(r, n, maxWidth, scratch) {
  const width = r.u8();
  if (width > maxWidth) throw new MalformedError(`stream width ${width} bits (at most ${maxWidth} allowed)`);
  const len = r.u32();
  const bytes = r.take(len);
  const available = 8 * len;
  if (Math.ceil(n / BLOCK) * PARAMETER_BITS > available) {
    throw new MalformedError(`${len} bytes cannot hold ${n} values`);
  }
  const values = scratch.valuesOf(n);
  const limit = 2 ** width;
  let pos = 0;
  for (let start = 0; start < n; start += BLOCK) {
    const end = Math.min(n, start + BLOCK);
    const k = peek(bytes, pos) & 63;
    pos += PARAMETER_BITS;
    if (k === ZERO_BLOCK) {
      values.fill(0, start, end);
      continue;
    }
    if (k > width) throw new MalformedError(`block parameter ${k} exceeds the stream width ${width}`);
    let over = false;
    for (let i = start; i < end; i++) {
      const window = peek(bytes, pos) & 0xffff;
      let v;
      if (window !== 0) {
        const q = 31 - Math.clz32(window & -window);
        pos += q + 1;
        // q < 16: with k <= 24 the value fits in int32 bit operations.
        v = k <= 24 ? (q << k) | bitsAt(bytes, pos, k) : q * 2 ** k + bitsAt(bytes, pos, k);
        pos += k;
      } else {
        pos += ESCAPE;
        v = bitsAt(bytes, pos, width);
        pos += width;
      }
      over ||= v >= limit;
      values[i] = v;
    }
    if (over) throw new MalformedError(`a value exceeds the stream width ${width}`);
    if (pos > available) throw new MalformedError(`the values run past the stream's ${len} bytes`);
  }
  if (Math.ceil(pos / 8) !== len) {
    throw new MalformedError(`the values take ${pos} bits of the stream's ${len} bytes`);
  }
  if ((pos & 7) !== 0 && bytes[len - 1] >> (pos & 7) !== 0) {
    throw new MalformedError('padding bits after the last value are not zero');
  }
  return values;
}
