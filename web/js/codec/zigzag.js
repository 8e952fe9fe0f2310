/**
 * Zigzag residuals (mirrors `proto/src/zigzag.rs`): `(now - prev) mod 2^bits` read as a
 * signed `bits`-bit number and zigzag-encoded (`0, -1, 1, -2, ...` as `0, 1, 2, 3, ...`).
 * @module
 */

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
