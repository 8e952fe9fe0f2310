/**
 * Reading one component's codes through its predictor (mirrors `proto/src/predict.rs` and the
 * `Predictor` enum of `proto/src/header.rs`).
 *
 * Stored values are what the prediction missed, `(code - prediction) mod 2^b`, zigzag-encoded:
 *
 * - `NONE` (0): the codes themselves.
 * - `PREVIOUS` (1): predicted by the previous particle's code in stream order (the first by 0).
 * - `BASE` (2): predicted by the same particle's code in the base frame (identity-ordered
 *   delta frames: the previous-frame predictor).
 * - `MORTON` (3): unordered positions, read by `unordered.js`, not here.
 * - `LINEAR` (4): identity-ordered delta positions after a delta frame, extrapolated from the
 *   base frame and its own base with each component's velocity gain (an i16 in units of 2^-12,
 *   read from the start of the channel payload by {@link readGains}; see {@link extrapolate}),
 *   modulo 2^16, then 2^b.
 * @module
 */

import { MalformedError } from './errors.js';
import { readStream } from './stream.js';

/** Predictor tags, as in the channel table. */
export const Predictor = Object.freeze({ NONE: 0, PREVIOUS: 1, BASE: 2, MORTON: 3, LINEAR: 4, GAPS: 5 });

/** Predictor names by tag, as in the golden sidecars (`predictor` field). */
export const PREDICTOR_NAMES = Object.freeze(['none', 'previous', 'base', 'morton', 'linear', 'gaps']);

/** Rust `Debug` names by tag, for messages. */
export const PREDICTOR_DEBUG_NAMES = ['None', 'Previous', 'Base', 'Morton', 'Linear', 'Gaps'];

/** Fraction bits of the `LINEAR` gains: an i16 in units of 2^-12. */
const GAIN_BITS = 12;

/**
 * `base + round(gain d)` (halves up) modulo 2^16, the extrapolation of `LINEAR`, where the
 * motion `d` is `base - before` modulo 2^16 read as a signed 16-bit number; exact in 32-bit
 * integers, since `|gain d|` is at most 2^30.
 * @param {number} base @param {number} before codes @param {number} gain in 2^-12
 * @returns {number}
 */
export function extrapolate(base, before, gain) {
  const d = ((base - before) << 16) >> 16;
  return (base + ((d * gain + (1 << (GAIN_BITS - 1))) >> GAIN_BITS)) & 0xffff;
}

/**
 * Reads the `LINEAR` predictor's gains, one i16 per component, from the start of a payload.
 * @param {import('./reader.js').Reader} r the channel's payload
 * @param {number} components
 * @returns {number[]}
 */
export function readGains(r, components) {
  const gains = [];
  for (let k = 0; k < components; k++) gains.push((r.u16() << 16) >> 16);
  return gains;
}

/**
 * Reads the stream of one component of `n` codes of `bits` bits predicted by `predictor`.
 * @param {import('./reader.js').Reader} r the channel's payload
 * @param {number} n particles
 * @param {number} bits 1 to 16
 * @param {number} predictor a tag of {@link Predictor}
 * @param {Uint16Array|null} base the base frame's codes of this component (`BASE`, `LINEAR`)
 * @param {Uint16Array|null} before the codes of the frame before the base (`LINEAR`)
 * @param {number} gain the component's velocity gain (`LINEAR`; see {@link readGains})
 * @param {import('./stream.js').Scratch} scratch
 * @returns {Uint16Array} the `n` codes
 * @throws {MalformedError}
 */
export function readCodes(r, n, bits, predictor, base, before, gain, scratch) {
  // The stream's width is at most `bits`, so every stored value fits in `bits` bits.
  const values = readStream(r, n, bits, scratch);
  const top = (1 << bits) - 1;
  const usable =
    predictor === Predictor.NONE ||
    predictor === Predictor.PREVIOUS ||
    (predictor === Predictor.BASE && base !== null && base.length === n) ||
    (predictor === Predictor.LINEAR && base !== null && before !== null && base.length === n && before.length === n);
  const codes = new Uint16Array(n);
  for (let i = 0; i < n; i++) codes[i] = values[i];
  if (!usable) {
    const name = PREDICTOR_DEBUG_NAMES[predictor] ?? String(predictor);
    throw new MalformedError(`predictor ${name} cannot apply to this channel`);
  }
  if (predictor === Predictor.PREVIOUS) {
    let prev = 0;
    for (let i = 0; i < n; i++) {
      const z = codes[i];
      prev = (prev + ((z >>> 1) ^ -(z & 1))) & top;
      codes[i] = prev;
    }
  } else if (predictor === Predictor.BASE) {
    for (let i = 0; i < n; i++) {
      const z = codes[i];
      codes[i] = (base[i] + ((z >>> 1) ^ -(z & 1))) & top;
    }
  } else if (predictor === Predictor.LINEAR) {
    for (let i = 0; i < n; i++) {
      const z = codes[i];
      codes[i] = (extrapolate(base[i], before[i], gain) + ((z >>> 1) ^ -(z & 1))) & top;
    }
  }
  return codes;
}
