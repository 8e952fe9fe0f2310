/**
 * Positions of unordered frames (mirrors `proto/src/unordered.rs`): particles sorted by the
 * Morton key of their quantised position, the sorted keys stored as differences from the
 * previous key (the first from 0) in one stream of values of up to `3 b` bits.
 * @module
 */

import { MalformedError } from './errors.js';
import { GATHER } from './morton.js';
import { stepOf } from './quantize.js';
import { readStream } from './stream.js';

const fround = Math.fround;
const TWO_24 = 16777216;

/**
 * Reads the positions stream of `n` particles and de-quantises it.
 * @param {import('./reader.js').Reader} r the position channel's payload
 * @param {number} n particles
 * @param {{min: number, max: number}[]} ranges the three axes' quantisation ranges
 * @param {number} bits position bits (1 to 16)
 * @param {import('./stream.js').Scratch} scratch
 * @returns {Float32Array} `3 n` values, x, y, z interleaved, in Morton order
 * @throws {MalformedError} if the stream is invalid or the keys sum past `3 b` bits
 */
export function readMortonPositions(r, n, ranges, bits, scratch) {
  const keyBits = 3 * bits;
  const values = readStream(r, n, keyBits, scratch);
  // The running key as two 24-bit halves (all bit operations stay in int32); it must stay
  // below 2^keyBits, i.e. the high half below 2^(keyBits - 24) (2^0 = 1: zero, for keyBits <= 24).
  const loLimit = keyBits >= 24 ? TWO_24 : 2 ** keyBits;
  const hiLimit = keyBits >= 24 ? 2 ** (keyBits - 24) : 1;
  const [mx, my, mz] = [ranges[0].min, ranges[1].min, ranges[2].min];
  const sx = stepOf(ranges[0].min, ranges[0].max, bits);
  const sy = stepOf(ranges[1].min, ranges[1].max, bits);
  const sz = stepOf(ranges[2].min, ranges[2].max, bits);
  const out = new Float32Array(3 * n);
  let lo = 0;
  let hi = 0;
  for (let i = 0; i < n; i++) {
    // The difference (below 2^48), split into halves and added with a carry between them.
    const diff = values[i];
    const dHi = Math.floor(diff / TWO_24);
    lo += diff - dHi * TWO_24;
    hi += dHi;
    hi += lo >>> 24;
    lo &= 0xffffff;
    if (hi >= hiLimit || (hi === 0 && lo >= loLimit)) {
      throw new MalformedError(`Morton key differences sum past ${keyBits} bits`);
    }
    const a = GATHER[lo & 0xfff];
    const b = GATHER[lo >>> 12];
    const c = GATHER[hi & 0xfff];
    const d = GATHER[hi >>> 12];
    const qx = (a & 15) | ((b & 15) << 4) | ((c & 15) << 8) | ((d & 15) << 12);
    const qy = ((a >>> 4) & 15) | (b & 0xf0) | ((c & 0xf0) << 4) | ((d & 0xf0) << 8);
    const qz = (a >>> 8) | ((b >>> 8) << 4) | ((c >>> 8) << 8) | ((d >>> 8) << 12);
    out[3 * i] = mx + fround(qx * sx);
    out[3 * i + 1] = my + fround(qy * sy);
    out[3 * i + 2] = mz + fround(qz * sz);
  }
  return out;
}
