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
    residuals: [Vec<u16>; 3],
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
    /// The same particle extrapolated from the base frame and the one before it:
    /// [`Predictor::Linear`].
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

/// Appends the streams of a channel's components, `codes` (1 or 3 of them, `bits` bits
/// each), component `k` predicted from `reference(k)`; returns the predictor.
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
        residuals(codes, bits, reference, v);
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

/// The values stored for `codes` predicted from `reference`, in `v`.
fn residuals(codes: &[u16], bits: u8, reference: Reference<'_>, v: &mut Vec<u16>) {
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
        Reference::Linear(base, before) => v.extend(
            codes.iter().zip(base).zip(before).map(|((&c, &b), &a)| zigzag_residual(c, extrapolate(b, a), bits)),
        ),
    }
}

/// `2 base - before`; [`zigzag_residual`] and [`apply_residual`] reduce it modulo `2^bits`.
#[inline]
fn extrapolate(base: u16, before: u16) -> u16 {
    base.wrapping_mul(2).wrapping_sub(before)
}

/// Reads the streams of a channel's components, `n` codes of `bits` bits each, predicted by
/// `predictor`, into `codes` (one vector per component, 1 or 3). `reference(k)` gives, for
/// component `k`, the base frame's codes for [`Predictor::Base`], and the codes of the frame
/// before it as well for [`Predictor::Linear`].
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
    match codes {
        [x, y, z] => stream::read_each(r, n, max_width, [x, y, z])?,
        [c] => stream::read_each(r, n, max_width, [c])?,
        _ => return Err(DecodeError::malformed(format!("{} components (1 or 3 allowed)", codes.len()))),
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
                for ((c, &b), &a) in codes.iter_mut().zip(base).zip(before) {
                    *c = apply_residual(*c, extrapolate(b, a), bits);
                }
            }
            (p, _) => return Err(DecodeError::malformed(format!("predictor {p:?} cannot apply to this channel"))),
        }
    }
    Ok(())
}
