/**
 * Morton (Z-order) keys (mirrors `proto/src/morton.rs`): the bits of three 16-bit
 * quantised coordinates interleaved, x in bit 0, y in bit 1 and z in bit 2 of each triple,
 * so a key has at most 48 bits and is exact as a JavaScript number.
 *
 * Decoding splits a key into four 12-bit chunks; each chunk holds 4 bits of each axis
 * (12 is a multiple of 3), looked up in a 4096-entry table.
 * @module
 */

/** Chunk (12 key bits) to `x4 | y4 << 4 | z4 << 8`: 4 bits of each axis. */
export const GATHER = new Uint16Array(4096);
for (let c = 0; c < 4096; c++) {
  let v = 0;
  for (let j = 0; j < 12; j++) {
    if (c & (1 << j)) v |= 1 << ((j % 3) * 4 + Math.floor(j / 3));
  }
  GATHER[c] = v;
}

/** 2^24, to split a key into two 24-bit halves without 64-bit integers. */
const TWO_24 = 16777216;

/**
 * The quantised position of a Morton key.
 * @param {number} key an integer below 2^48
 * @param {Uint16Array|number[]} out receives `[x, y, z]` at `out[at]`, `out[at + 1]`, `out[at + 2]`
 * @param {number} [at=0]
 */
export function decodeKey(key, out, at = 0) {
  const lo = key % TWO_24;
  const hi = (key - lo) / TWO_24;
  const a = GATHER[lo & 0xfff];
  const b = GATHER[lo >>> 12];
  const c = GATHER[hi & 0xfff];
  const d = GATHER[hi >>> 12];
  out[at] = (a & 15) | ((b & 15) << 4) | ((c & 15) << 8) | ((d & 15) << 12);
  out[at + 1] = ((a >>> 4) & 15) | (b & 0xf0) | ((c & 0xf0) << 4) | ((d & 0xf0) << 8);
  out[at + 2] = (a >>> 8) | ((b >>> 8) << 4) | ((c >>> 8) << 8) | ((d >>> 8) << 12);
}

/**
 * The Morton key of one quantised position (for tests and tools; the decoder only decodes keys).
 * @param {number} x @param {number} y @param {number} z codes of 0 to 65535
 * @returns {number} the key, below 2^48
 */
export function encodeKey(x, y, z) {
  let key = 0;
  for (let i = 15; i >= 0; i--) {
    key = key * 8 + (((z >>> i) & 1) << 2) + (((y >>> i) & 1) << 1) + ((x >>> i) & 1);
  }
  return key;
}
