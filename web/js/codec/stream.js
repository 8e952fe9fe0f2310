/**
 * Streams: how a channel's payload stores `n` unsigned values as byte planes
 * (mirrors `proto/src/stream.rs`).
 *
 * | offset | size | field |
 * |---:|---:|---|
 * | 0 | 1 | width `w`: bytes per value |
 * | 1 | ... | `w` planes, each: method u8 (0 stored, 1 LZ4 block), length u32, then `length` bytes |
 *
 * Every plane must come out as exactly `n` bytes.
 * @module
 */

import { MalformedError } from './errors.js';
import { decompressBlockInto } from './lz4.js';

const STORED = 0;
const LZ4 = 1;

/** Scratch buffers a decoder reuses from frame to frame. */
export class Scratch {
  constructor() {
    /** @type {Uint8Array} */
    this.planes = new Uint8Array(0);
  }

  /**
   * A buffer of at least `len` bytes (grown, never shrunk).
   * @param {number} len
   * @returns {Uint8Array}
   */
  planesOf(len) {
    if (this.planes.length < len) this.planes = new Uint8Array(Math.max(len, this.planes.length * 2));
    return this.planes;
  }
}

/**
 * Reads a stream of `n` values of at most `maxWidth` bytes from `r`. The planes land in
 * `scratch.planes` (`width * n` bytes, plane after plane).
 *
 * Allocation is bounded by `n` (checked by the caller against its limit) and by the
 * bytes present: an LZ4 plane whose length could not hold `n` bytes (LZ4 expands at most
 * about 255-fold) is refused before anything is allocated.
 * @param {import('./reader.js').Reader} r the channel payload
 * @param {number} n values
 * @param {number} maxWidth most bytes per value allowed
 * @param {Scratch} scratch
 * @returns {number} the width
 * @throws {MalformedError}
 */
export function readStream(r, n, maxWidth, scratch) {
  const width = r.u8();
  if (width < 1 || width > maxWidth) {
    throw new MalformedError(`stream width ${width} (1 to ${maxWidth} allowed)`);
  }
  for (let k = 0; k < width; k++) {
    const method = r.u8();
    const len = r.u32();
    const data = r.take(len);
    if (method === STORED) {
      if (len !== n) throw new MalformedError(`stored plane ${k} has ${len} bytes, not ${n}`);
      scratch.planesOf(width * n).set(data, k * n);
    } else if (method === LZ4) {
      if (n > 256 * len + 64) {
        throw new MalformedError(`${len} LZ4 bytes cannot hold a plane of ${n} bytes`);
      }
      const out = scratch.planesOf(width * n).subarray(k * n, (k + 1) * n);
      let got;
      try {
        got = decompressBlockInto(data, out);
      } catch (e) {
        throw new MalformedError(`plane ${k}: LZ4: ${e.message}`);
      }
      if (got !== n) throw new MalformedError(`plane ${k} decompresses to ${got} bytes, not ${n}`);
    } else {
      throw new MalformedError(`plane ${k}: unknown method ${method}`);
    }
  }
  return width;
}
