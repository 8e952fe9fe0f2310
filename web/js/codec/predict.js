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
 * - `LINEAR` (4): identity-ordered delta positions after a delta frame, predicted at constant
 *   velocity, `2 base - before` (modulo 2^16, then 2^b), from the base frame and its own base.
 * @module
 */

import { MalformedError } from './errors.js';
import { readStream } from './stream.js';

/** Predictor tags, as in the channel table. */
export const Predictor = Object.freeze({ NONE: 0, PREVIOUS: 1, BASE: 2, MORTON: 3, LINEAR: 4 });

/** Predictor names by tag, as in the golden sidecars (`predictor` field). */
export const PREDICTOR_NAMES = Object.freeze(['none', 'previous', 'base', 'morton', 'linear']);

/** Rust `Debug` names by tag, for messages. */
export const PREDICTOR_DEBUG_NAMES = ['None', 'Previous', 'Base', 'Morton', 'Linear'];

/**
 * `2 base - before` modulo 2^16, the constant-velocity extrapolation.
 * @param {number} base @param {number} before codes
 * @returns {number}
 */
export function extrapolate(base, before) {
  return (2 * base - before) & 0xffff;
}

/**
 * Reads the stream of one component of `n` codes of `bits` bits predicted by `predictor`.
 * @param {import('./reader.js').Reader} r the channel's payload
 * @param {number} n particles
 * @param {number} bits 1 to 16
 * @param {number} predictor a tag of {@link Predictor}
 * @param {Uint16Array|null} base the base frame's codes of this component (`BASE`, `LINEAR`)
 * @param {Uint16Array|null} before the codes of the frame before the base (`LINEAR`)
 * @param {import('./stream.js').Scratch} scratch
 * @returns {Uint16Array} the `n` codes
 * @throws {MalformedError}
 */
export function readCodes(r, n, bits, predictor, base, before, scratch) {
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
      codes[i] = (((2 * base[i] - before[i]) & 0xffff) + ((z >>> 1) ^ -(z & 1))) & top;
    }
  }
  return codes;
}
