//! Writing and reading a channel's codes as streams, one per component, through its predictor.

use crate::error::DecodeError;
use crate::header::Predictor;
use crate::reader::Reader;
use crate::stream;
use crate::zigzag::{apply_residual, zigzag_residual};

/// Scratch buffers reused from frame to frame.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    /// Residuals of each component.
    residuals: [Vec<u16>; 4],
    /// The second and third components' streams while they are written.
    streams: [Vec<u8>; 2],
}

/// Where a component's codes are predicted from.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Reference<'a> {
    /// The previous particle in stream order, particles taken in `order` when given:
    /// [`Predictor::Previous`].
    Previous(Option<&'a [u32]>),
    /// The same particle in the base frame: [`Predictor::Base`].
    Base(&'a [u16]),
    /// The same particle extrapolated from the base frame and the one before it, with a
    /// velocity gain the encoder fits: [`Predictor::Linear`].
    Linear(&'a [u16], &'a [u16]),
}

impl Reference<'_> {
    pub(crate) fn predictor(&self) -> Predictor {
        match self {
            Reference::Previous(_) => Predictor::Previous,
            Reference::Base(_) => Predictor::Base,
            Reference::Linear(..) => Predictor::Linear,
        }
    }
}

/// Fraction bits of the velocity gains of [`Predictor::Linear`]: a gain is an i16 in units of
/// 2^-12, from -8 to just under 8, fine enough that a motion of 1,000 codes is predicted to an
/// eighth of a code, and small enough that the prediction is exact in 32-bit integers (in a
/// JavaScript decoder's too) and every stored value is a valid gain.
const GAIN_BITS: u32 = 12;
/// A velocity gain of 1.
const GAIN_ONE: i16 = 1 << GAIN_BITS;
/// The gain is fitted on every this many particles: a quarter of the work, and tens of
/// thousands of particles in a large frame still pin it to well under 1 %.
const FIT_STRIDE: usize = 4;

/// Appends the streams of a channel's components, `codes` (1 to 4 of them, `bits` bits
/// each), component `k` predicted from `reference(k)`; returns the predictor. Three
/// components are written side by side ([`stream::write_each`]), any other count one stream
/// after another. With [`Reference::Linear`] the payload starts with each component's gain (i16).
pub(crate) fn write<'a>(
    out: &mut Vec<u8>,
    codes: &[Vec<u16>],
    bits: u8,
    reference: impl Fn(usize) -> Reference<'a>,
    s: &mut Scratch,
) -> Predictor {
    let mut predictor = Predictor::None;
    for (k, (codes, v)) in codes.iter().zip(&mut s.residuals).enumerate() {
        let reference = reference(k);
        predictor = reference.predictor();
        if let Some(gain) = residuals(codes, bits, reference, v) {
            out.extend_from_slice(&gain.to_le_bytes());
        }
    }
    let r = &s.residuals;
    match codes.len() {
        3 => {
            let [y, z] = &mut s.streams;
            stream::write_each([out, y, z], [&r[0], &r[1], &r[2]]);
        }
        count => r[..count].iter().for_each(|v| stream::write(out, v)),
    }
    predictor
}

/// The values stored for `codes` predicted from `reference`, in `v`; for
/// [`Reference::Linear`], the gain they were predicted with.
fn residuals(codes: &[u16], bits: u8, reference: Reference<'_>, v: &mut Vec<u16>) -> Option<i16> {
    v.clear();
    match reference {
        Reference::Previous(None) => {
            let mut prev = 0;
            v.extend(codes.iter().map(|&c| {
                let r = zigzag_residual(c, prev, bits);
                prev = c;
                r
            }));
        }
        Reference::Previous(Some(order)) => {
            let mut prev = 0;
            v.extend(order.iter().map(|&i| {
                let c = codes[i as usize];
                let r = zigzag_residual(c, prev, bits);
                prev = c;
                r
            }));
        }
        Reference::Base(base) => {
            v.extend(codes.iter().zip(base).map(|(&c, &b)| zigzag_residual(c, b, bits)));
        }
        Reference::Linear(base, before) => {
            let gain = fit_gain(codes, base, before);
            v.extend(
                codes
                    .iter()
                    .zip(base)
                    .zip(before)
                    .map(|((&c, &b), &a)| zigzag_residual(c, extrapolate(b, a, gain), bits)),
            );
            return Some(gain);
        }
    }
    None
}

/// The velocity gain (in 2^-12) that best predicts `codes` from `base + gain (base - before)`
/// in the least-squares sense over every [`FIT_STRIDE`]th particle, rounded and clamped to an
/// i16: 1 for frames equally spaced in time at constant velocity, the ratio of the intervals
/// for unequal spacing (a subscriber that skipped frames), less where the motion is damped.
/// 0 if nothing moved. Only the encoder fits; the decoder reads the result.
fn fit_gain(codes: &[u16], base: &[u16], before: &[u16]) -> i16 {
    // Each product is below 2^32 in magnitude and at most 2^30 are summed (frames hold under
    // 2^32 particles), so the sums fit an i64 exactly.
    let (mut dy, mut dd) = (0i64, 0i64);
    for ((c, b), a) in sample(codes).zip(sample(base)).zip(sample(before)) {
        let d = b - a;
        dy += d * (c - b);
        dd += d * d;
    }
    if dd == 0 {
        return 0;
    }
    let gain = (dy as f64 / dd as f64 * f64::from(GAIN_ONE)).round();
    gain.clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
}

/// Every [`FIT_STRIDE`]th code, widened.
fn sample(codes: &[u16]) -> impl Iterator<Item = i64> + '_ {
    codes.iter().step_by(FIT_STRIDE).map(|&c| i64::from(c))
}

/// `base + round(gain d)`, rounding halves up, modulo 2^16, where the motion `d` is
/// `base - before` modulo 2^16 read as a signed 16-bit number and `gain` is in 2^-12;
/// [`zigzag_residual`] and [`apply_residual`] reduce it modulo `2^bits`. `|gain d|` is at most
/// 2^30: nothing overflows. (Written in i32 throughout, which the compiler vectorises.)
#[inline]
fn extrapolate(base: u16, before: u16, gain: i16) -> u16 {
    let d = ((i32::from(base) - i32::from(before)) << 16) >> 16;
    let step = (d * i32::from(gain) + (1 << (GAIN_BITS - 1))) >> GAIN_BITS;
    (i32::from(base) + step) as u16
}

/// Reads the streams of a channel's components, `n` codes of `bits` bits each, predicted by
/// `predictor`, into `codes` (one vector per component, 1 to 4). `reference(k)` gives, for
/// component `k`, the base frame's codes for [`Predictor::Base`], and the codes of the frame
/// before it as well for [`Predictor::Linear`], whose gains are read from the payload's start.
pub(crate) fn read<'a>(
    r: &mut Reader<'_>,
    n: usize,
    bits: u8,
    predictor: Predictor,
    reference: impl Fn(usize) -> (Option<&'a [u16]>, Option<&'a [u16]>),
    codes: &mut [Vec<u16>],
) -> Result<(), DecodeError> {
    // The streams' width is at most `bits`, so every stored value fits in `bits` bits.
    let max_width = u32::from(bits);
    let mut gains = [0; 4];
    if predictor == Predictor::Linear {
        for gain in gains.iter_mut().take(codes.len()) {
            *gain = r.u16()? as i16;
        }
    }
    match codes {
        [x, y, z] => stream::read_each(r, n, max_width, [x, y, z])?,
        _ => {
            for c in codes.iter_mut() {
                stream::read_each(r, n, max_width, [c])?;
            }
        }
    }
    for (k, codes) in codes.iter_mut().enumerate() {
        match (predictor, reference(k)) {
            (Predictor::None, _) => {}
            (Predictor::Previous, _) => {
                let mut prev = 0;
                for c in codes.iter_mut() {
                    prev = apply_residual(*c, prev, bits);
                    *c = prev;
                }
            }
            (Predictor::Base, (Some(base), _)) if base.len() == n => {
                for (c, &b) in codes.iter_mut().zip(base) {
                    *c = apply_residual(*c, b, bits);
                }
            }
            (Predictor::Linear, (Some(base), Some(before))) if base.len() == n && before.len() == n => {
                let gain = gains[k];
                for ((c, &b), &a) in codes.iter_mut().zip(base).zip(before) {
                    *c = apply_residual(*c, extrapolate(b, a, gain), bits);
                }
            }
            (p, _) => return Err(DecodeError::malformed(format!("predictor {p:?} cannot apply to this channel"))),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(base, before, gain, prediction)`; `web/test/codec.test.mjs` checks the JavaScript
    /// decoder's extrapolation against the same table.
    const CASES: [(u16, u16, i16, u16); 9] = [
        (100, 90, GAIN_ONE, 110),
        (100, 90, -GAIN_ONE, 90),
        (100, 90, 3 * GAIN_ONE / 2, 115),
        (100, 99, GAIN_ONE / 2, 101),
        (100, 101, GAIN_ONE / 2, 100),
        (100, 101, -GAIN_ONE / 2, 101),
        // Motion across the wrap: 65,535 after 0 is one code down.
        (65_535, 0, GAIN_ONE, 65_534),
        // A motion of 40,000 codes reads as -25,536.
        (50_000, 10_000, GAIN_ONE, 24_464),
        // 3 - 59,997 is 5,539 modulo 2^16; 3 - 8 * 5,539 = -44,309, 21,227 modulo 2^16.
        (3, 60_000, i16::MIN, 21_227),
    ];

    #[test]
    fn extrapolation_rounds_halves_up_and_wraps() {
        for (base, before, gain, want) in CASES {
            assert_eq!(extrapolate(base, before, gain), want, "extrapolate({base}, {before}, {gain})");
        }
    }

    #[test]
    fn the_fitted_gain_is_the_ratio_of_the_intervals() {
        let before: Vec<u16> = (0..1000).map(|i| 1000 + i).collect();
        let base: Vec<u16> = before.iter().enumerate().map(|(i, &a)| a + (i % 7) as u16 * 10).collect();
        let now: Vec<u16> = base.iter().zip(&before).map(|(&b, &a)| b + 3 * (b - a)).collect();
        assert_eq!(fit_gain(&now, &base, &before), 3 * GAIN_ONE);
        assert_eq!(fit_gain(&base, &base, &base), 0, "nothing moved");
        let far: Vec<u16> = base.iter().zip(&before).map(|(&b, &a)| b + 20 * (b - a)).collect();
        assert_eq!(fit_gain(&far, &base, &before), i16::MAX, "clamped");
    }
}
