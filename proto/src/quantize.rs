//! Uniform scalar quantisation of one component to `b`-bit codes.
//!
//! A component with range `[min, max]` and `b` bits has `L = 2^b - 1` steps of
//! `step = (max - min) / L`. Encoding rounds to the nearest code and clamps to `0..=L`
//! (NaN becomes code 0); decoding computes, in f32 with one rounding per operation
//! (no fused multiply-add), `step = (max - min) / L` and `value = min + code * step`.
//! A decoder in another language must round the same way (in JavaScript, `Math.fround`
//! after each operation) to reproduce the golden frames bit for bit.
//!
//! The error of a value inside the range is at most half a step, the `max_error` in the
//! channel table, plus f32 rounding of a few ulps of the range's magnitude. Values
//! outside the range are clamped to its ends.

use crate::header::ComponentRange;

/// Quantises and de-quantises one component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantizer {
    /// Value of code 0.
    pub min: f32,
    /// Value of the largest code.
    pub max: f32,
    /// Bits per code (1 to 16).
    pub bits: u8,
}

impl Quantizer {
    /// The largest code, `2^bits - 1`.
    pub fn largest_code(&self) -> u32 {
        (1u32 << self.bits) - 1
    }

    /// Distance between neighbouring codes' values, in the channel's unit.
    pub fn step(&self) -> f32 {
        (self.max - self.min) / self.largest_code() as f32
    }

    /// Half a step: the largest error of a value inside the range.
    pub fn max_error(&self) -> f32 {
        self.step() * 0.5
    }

    /// The range as written in the channel table.
    pub fn range(&self) -> ComponentRange {
        ComponentRange { min: self.min, max: self.max, max_error: self.max_error() }
    }

    /// Codes of `values`, appended to `out`.
    pub fn encode_into(&self, values: impl Iterator<Item = f32>, out: &mut Vec<u16>) {
        let coder = self.coder();
        out.extend(values.map(|v| coder.code(v)));
    }

    /// The encoding half, with the scale computed once.
    pub(crate) fn coder(&self) -> Coder {
        let span = self.max - self.min;
        let scale = if span > 0.0 { self.largest_code() as f32 / span } else { 0.0 };
        Coder { min: self.min, scale, top: self.largest_code() as u16 }
    }

    /// The value of one code.
    pub fn decode(&self, code: u16) -> f32 {
        self.min + f32::from(code) * self.step()
    }
}

/// Codes values of one [`Quantizer`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Coder {
    min: f32,
    scale: f32,
    top: u16,
}

impl Coder {
    /// The nearest code of `v`, clamped to the range.
    #[inline(always)]
    pub(crate) fn code(&self, v: f32) -> u16 {
        // `as u16` saturates negatives to 0 and turns NaN into 0, which `f32::clamp` would
        // keep; taking the minimum after the cast needs no branch.
        (((v - self.min) * self.scale + 0.5) as u16).min(self.top)
    }
}

/// The smallest range holding every finite value of `values` (`[0, 0]` if none is finite).
pub(crate) fn finite_range(values: impl Iterator<Item = f32>) -> (f32, f32) {
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for v in values {
        // NaN compares false and is skipped; infinities are skipped explicitly.
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if lo > hi { (0.0, 0.0) } else { (lo, hi) }
}

/// What a channel-table range describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RangeForm {
    /// Quantised floats: the error is half a step.
    Quantised,
    /// Raw u8 values: exactly `[0, 255]`, 8 bits, error 0.
    ExactU8,
    /// A grid's extent on one axis: finite, ordered, error 0.
    Extent,
}

/// Checks one channel-table range on its own: finite ends, `min <= max`, a finite step,
/// and the stated maximum error equal to half a step (or exactly the raw u8 range
/// `[0, 255]`, 8 bits, error 0, for an exact channel; or error 0 for a grid's extent).
/// The redundant error field catches most corruptions of the range.
pub(crate) fn check_range(range: &ComponentRange, bits: u8, form: RangeForm) -> Result<(), String> {
    let ComponentRange { min, max, max_error } = *range;
    if form == RangeForm::Extent {
        if !(min.is_finite() && max.is_finite() && min <= max && max_error == 0.0) {
            return Err(format!(
                "a grid extent is finite and ordered with error 0, not [{min}, {max}], error {max_error}"
            ));
        }
        return Ok(());
    }
    if form == RangeForm::ExactU8 {
        if (min, max, max_error, bits) != (0.0, 255.0, 0.0, 8) {
            return Err(format!(
                "a raw u8 channel has range [0, 255], 8 bits and error 0, not [{min}, {max}], {bits} bits, error {max_error}"
            ));
        }
        return Ok(());
    }
    if !(min.is_finite() && max.is_finite() && min <= max) {
        return Err(format!("invalid range [{min}, {max}]"));
    }
    let q = Quantizer { min, max, bits };
    let expected = q.max_error();
    if !expected.is_finite() {
        return Err(format!("range [{min}, {max}] is too wide for f32 steps"));
    }
    if max_error.to_bits() != expected.to_bits() {
        return Err(format!(
            "maximum error {max_error} is not half the step of [{min}, {max}] at {bits} bits ({expected})"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_and_midpoints_round_to_nearest_code() {
        let q = Quantizer { min: -1.0, max: 1.0, bits: 8 };
        let mut codes = Vec::new();
        q.encode_into([-1.0, 1.0, 0.0, -5.0, 5.0, f32::NAN].into_iter(), &mut codes);
        assert_eq!(codes, [0, 255, 128, 0, 255, 0]);
        assert_eq!(q.decode(0), -1.0);
        assert_eq!(q.decode(255), 1.0);
        assert!((q.decode(128) - 0.0).abs() <= q.max_error() + f32::EPSILON, "a tie, up to rounding");
    }

    #[test]
    fn a_constant_channel_has_zero_error() {
        let q = Quantizer { min: 3.0, max: 3.0, bits: 10 };
        let mut codes = Vec::new();
        q.encode_into([3.0, 3.0].into_iter(), &mut codes);
        assert_eq!(codes, [0, 0]);
        assert_eq!(q.decode(0), 3.0);
        assert_eq!(q.max_error(), 0.0);
    }

    #[test]
    fn ranges_are_checked() {
        let good = Quantizer { min: 0.0, max: 2.0, bits: 16 }.range();
        assert!(check_range(&good, 16, RangeForm::Quantised).is_ok());
        assert!(check_range(&good, 15, RangeForm::Quantised).is_err(), "error must match the bits");
        assert!(check_range(&Quantizer { min: 2.0, max: 2.0, bits: 16 }.range(), 16, RangeForm::Quantised).is_ok());
        assert!(check_range(&ComponentRange { min: 3.0, ..good }, 16, RangeForm::Quantised).is_err());
        assert!(check_range(&ComponentRange { max: f32::NAN, ..good }, 16, RangeForm::Quantised).is_err());
        let wide = Quantizer { min: -3e38, max: 3e38, bits: 1 }.range();
        assert!(check_range(&wide, 1, RangeForm::Quantised).is_err());
        let phase = ComponentRange { min: 0.0, max: 255.0, max_error: 0.0 };
        assert!(check_range(&phase, 8, RangeForm::ExactU8).is_ok());
        assert!(check_range(&phase, 8, RangeForm::Quantised).is_err());
        let extent = ComponentRange { min: -1.0, max: 3.0, max_error: 0.0 };
        assert!(check_range(&extent, 16, RangeForm::Extent).is_ok());
        assert!(check_range(&ComponentRange { max: -2.0, ..extent }, 16, RangeForm::Extent).is_err());
    }

    #[test]
    fn finite_range_skips_nan_and_infinity() {
        assert_eq!(finite_range([1.0, f32::NAN, -2.0, f32::INFINITY].into_iter()), (-2.0, 1.0));
        assert_eq!(finite_range([f32::NAN].into_iter()), (0.0, 0.0));
    }
}
