/**
 * De-quantisation of `b`-bit codes (mirrors `proto/src/quantize.rs`), bit for bit.
 *
 * A component with range `[min, max]` and `b` bits has `L = 2^b - 1` steps of
 * `step = (max - min) / L`, and code `c` decodes to `min + c * step`, each operation
 * rounded to f32 (`Math.fround` after each one; JavaScript has no fused multiply-add, and
 * rounding an exact-in-f64 result once to f32 equals the f32 operation).
 * @module
 */

const fround = Math.fround;

/**
 * The distance between neighbouring codes' values, as Rust's `Quantizer::step` computes it in f32.
 * @param {number} min range minimum (an f32 value)
 * @param {number} max range maximum (an f32 value)
 * @param {number} bits 1 to 16
 * @returns {number} an f32 value
 */
export function stepOf(min, max, bits) {
  return fround(fround(max - min) / ((1 << bits) - 1));
}

/**
 * Half a step: the largest error of a value inside the range (an f32 value).
 * @param {number} min @param {number} max @param {number} bits
 * @returns {number}
 */
export function maxErrorOf(min, max, bits) {
  return fround(stepOf(min, max, bits) * 0.5);
}

/**
 * The value of one code: `min + code * step` in f32.
 * @param {number} min @param {number} step from {@link stepOf} @param {number} code
 * @returns {number}
 */
export function dequantise(min, step, code) {
  return fround(min + fround(code * step));
}

/**
 * An f32 value as Rust's `Display` writes it (shortest digits that read back as the same f32,
 * no exponent), so error messages match the Rust decoder's.
 * @param {number} v an f32 value
 * @returns {string}
 */
export function formatF32(v) {
  if (Number.isNaN(v)) return 'NaN';
  if (!Number.isFinite(v)) return v > 0 ? 'inf' : '-inf';
  if (v === 0) return Object.is(v, -0) ? '-0' : '0';
  const x = Math.abs(v);
  // The f32 neighbours' midpoints (exact in f64): a decimal whose f64 reading lies strictly
  // between them reads back as v (rounding is monotonic); on one, it ties to even. Messages
  // only: a decimal within half an f64 ulp of a midpoint may be judged as if on it.
  const f = new Float32Array([x]);
  const u = new Uint32Array(f.buffer);
  const bits = u[0];
  u[0] = bits - 1;
  const lo = (x + f[0]) / 2;
  u[0] = bits + 1;
  const hi = (x + f[0]) / 2;
  const inside = (d) => (d > lo && d < hi) || ((d === lo || d === hi) && (bits & 1) === 0);
  let digits = '';
  let exp = 0;
  for (let p = 1; p <= 9 && digits === ''; p++) {
    const [m, e] = x.toExponential(p - 1).split('e');
    const mantissa = Number(m.replace('.', ''));
    exp = Number(e) - (p - 1);
    // The nearest p-digit decimal first; next to a power of two (uneven gaps) a neighbour may fit.
    for (const c of [mantissa, mantissa - 1, mantissa + 1]) {
      if (inside(Number(`${c}e${exp}`))) {
        digits = String(c);
        break;
      }
    }
  }
  if (digits === '') [digits, exp] = [String(x), 0]; // not reached: 9 digits always suffice
  const trimmed = digits.replace(/0+$/, '');
  exp += digits.length - trimmed.length;
  const point = trimmed.length + exp; // digits before the decimal point
  let out;
  if (point <= 0) out = `0.${'0'.repeat(-point)}${trimmed}`;
  else if (exp >= 0) out = trimmed + '0'.repeat(exp);
  else out = `${trimmed.slice(0, point)}.${trimmed.slice(point)}`;
  return v < 0 ? `-${out}` : out;
}

/** What a channel-table range describes (Rust `RangeForm`). */
export const RangeForm = Object.freeze({ QUANTISED: 0, EXACT_U8: 1, EXTENT: 2 });

/**
 * Checks one channel-table range on its own, as Rust's `check_range`: finite ends, `min <= max`,
 * a finite step and the stated maximum error equal to half a step; exactly `[0, 255]`, 8 bits,
 * error 0 for an exact channel; error 0 for a grid's extent.
 * @param {{min: number, max: number, maxError: number}} range
 * @param {number} bits
 * @param {number} form a {@link RangeForm}
 * @returns {string|null} what is wrong, or null
 */
export function checkRange(range, bits, form) {
  const { min, max, maxError } = range;
  const [a, b, e] = [() => formatF32(min), () => formatF32(max), () => formatF32(maxError)]; // only on errors
  if (form === RangeForm.EXTENT) {
    if (Number.isFinite(min) && Number.isFinite(max) && min <= max && maxError === 0) return null;
    return `a grid extent is finite and ordered with error 0, not [${a()}, ${b()}], error ${e()}`;
  }
  if (form === RangeForm.EXACT_U8) {
    if (min === 0 && max === 255 && maxError === 0 && bits === 8) return null;
    return `a raw u8 channel has range [0, 255], 8 bits and error 0, not [${a()}, ${b()}], ${bits} bits, error ${e()}`;
  }
  if (!(Number.isFinite(min) && Number.isFinite(max) && min <= max)) return `invalid range [${a()}, ${b()}]`;
  const expected = maxErrorOf(min, max, bits);
  if (!Number.isFinite(expected)) return `range [${a()}, ${b()}] is too wide for f32 steps`;
  // Object.is compares like Rust's to_bits here: +0 and -0 differ, and neither side is NaN
  // but maxError (which then differs, as its bits differ from any finite value's).
  if (!Object.is(maxError, expected)) {
    return `maximum error ${e()} is not half the step of [${a()}, ${b()}] at ${bits} bits (${formatF32(expected)})`;
  }
  return null;
}

/**
 * Whether two quantisers are the same: equal bits and bit-identical range ends (so 0 and -0
 * differ, as their steps may). Ranges come from the channel table and are finite.
 * @param {{min: number, max: number}} a @param {number} aBits
 * @param {{min: number, max: number}} b @param {number} bBits
 * @returns {boolean}
 */
export function sameQuantizer(a, aBits, b, bBits) {
  return aBits === bBits && Object.is(a.min, b.min) && Object.is(a.max, b.max);
}

/**
 * De-quantises one component's codes into `out[offset + stride * i]`.
 * @param {Uint16Array} codes
 * @param {{min: number, max: number}} range
 * @param {number} bits
 * @param {Float32Array} out
 * @param {number} offset first index written
 * @param {number} stride distance between written indices (3 for interleaved x, y, z)
 */
export function dequantiseInto(codes, range, bits, out, offset, stride) {
  const min = range.min;
  const step = stepOf(range.min, range.max, bits);
  const n = codes.length;
  for (let i = 0, j = offset; i < n; i++, j += stride) out[j] = min + fround(codes[i] * step);
}
