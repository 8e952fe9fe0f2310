/**
 * Byte planes and zigzag residuals (mirrors `proto/src/shuffle.rs`).
 *
 * A stream of `n` values of `w` bytes is stored as `w` planes of `n` bytes: byte 0
 * (least significant) of every value, then byte 1 of every value, and so on.
 * Residuals are `(now - prev) mod 2^bits` read as a signed `bits`-bit number and
 * zigzag-encoded (`0, -1, 1, -2, ...` as `0, 1, 2, 3, ...`).
 * @module
 */

/**
 * Bytes needed to hold `max` (at least 1).
 * @param {number} max a non-negative integer below 2^53
 * @returns {number}
 */
export function widthOf(max) {
  let w = 1;
  while (max >= 2 ** (8 * w)) w++;
  return w;
}

/**
 * Rebuilds 16-bit values from `width` (1 or 2) planes of `n` bytes each.
 * @param {Uint8Array} planes at least `width * n` bytes, plane after plane
 * @param {number} width 1 or 2
 * @param {number} n values
 * @param {Uint16Array} out receives `n` values
 */
export function joinPlanesU16(planes, width, n, out) {
  if (width === 1) {
    for (let i = 0; i < n; i++) out[i] = planes[i];
  } else {
    for (let i = 0; i < n; i++) out[i] = planes[i] | (planes[n + i] << 8);
  }
}

/**
 * Rebuilds unsigned values of up to 6 bytes (below 2^48, so exact as JS numbers) from
 * `width` planes of `n` bytes each. (Rust joins up to 8 bytes into u64; the format never
 * stores wider than 6, which the caller checks first.)
 * @param {Uint8Array} planes at least `width * n` bytes, plane after plane
 * @param {number} width 1 to 6
 * @param {number} n values
 * @param {Float64Array} out receives `n` values
 */
export function joinPlanesU48(planes, width, n, out) {
  if (width < 1 || width > 6) throw new RangeError(`width ${width} (1 to 6 supported)`);
  // Low 3 bytes and high 3 bytes as 24-bit integers, so all bit operations stay in int32.
  const lowW = Math.min(width, 3);
  for (let i = 0; i < n; i++) {
    let lo = 0;
    for (let k = 0; k < lowW; k++) lo |= planes[k * n + i] << (8 * k);
    let hi = 0;
    for (let k = 3; k < width; k++) hi |= planes[k * n + i] << (8 * (k - 3));
    out[i] = hi * 16777216 + lo;
  }
}

/**
 * `(now - prev) mod 2^bits` as a signed `bits`-bit number, zigzag-encoded.
 * @param {number} now code (0 to 2^bits - 1)
 * @param {number} prev its prediction
 * @param {number} bits 1 to 16
 * @returns {number} the residual, within `bits` bits
 */
export function zigzagResidual(now, prev, bits) {
  const shift = 32 - bits;
  const s = ((now - prev) << shift) >> shift;
  return ((s << 1) ^ (s >> 31)) & 0xffff;
}

/**
 * Inverse of {@link zigzagResidual}: `prev + unzigzag(residual)` modulo `2^bits`.
 * @param {number} residual stored value (0 to 65535)
 * @param {number} prev the prediction
 * @param {number} bits 1 to 16
 * @returns {number} the code
 */
export function applyResidual(residual, prev, bits) {
  const s = (residual >>> 1) ^ -(residual & 1);
  return (prev + s) & ((1 << bits) - 1);
}

/**
 * Zigzag decoding alone: `0, 1, 2, 3, ...` to `0, -1, 1, -2, ...`.
 * @param {number} z a non-negative int32
 * @returns {number}
 */
export function unzigzag(z) {
  return (z >>> 1) ^ -(z & 1);
}
