//! Writing and reading one component's codes as a stream, through its predictor.

use crate::error::DecodeError;
use crate::header::Predictor;
use crate::reader::Reader;
use crate::stream;
use crate::zigzag::{apply_residual, zigzag_residual};

/// Scratch buffers reused from frame to frame.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    values: Vec<u64>,
}

/// Where a component's codes are predicted from.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Reference<'a> {
    /// Nothing: [`Predictor::None`].
    Nothing,
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
            Reference::Nothing => Predictor::None,
            Reference::Previous(_) => Predictor::Previous,
            Reference::Base(_) => Predictor::Base,
            Reference::Linear(..) => Predictor::Linear,
        }
    }
}

/// Appends the stream of one component's `codes` (`bits` bits each), predicted from `reference`.
pub(crate) fn write(out: &mut Vec<u8>, codes: &[u16], bits: u8, reference: Reference<'_>, s: &mut Scratch) {
    let v = &mut s.values;
    v.clear();
    match reference {
        Reference::Nothing => v.extend(codes.iter().map(|&c| u64::from(c))),
        Reference::Previous(None) => {
            let mut prev = 0;
            v.extend(codes.iter().map(|&c| {
                let r = zigzag_residual(c, prev, bits);
                prev = c;
                u64::from(r)
            }));
        }
        Reference::Previous(Some(order)) => {
            let mut prev = 0;
            v.extend(order.iter().map(|&i| {
                let c = codes[i as usize];
                let r = zigzag_residual(c, prev, bits);
                prev = c;
                u64::from(r)
            }));
        }
        Reference::Base(base) => {
            v.extend(codes.iter().zip(base).map(|(&c, &b)| u64::from(zigzag_residual(c, b, bits))));
        }
        Reference::Linear(base, before) => v.extend(
            codes
                .iter()
                .zip(base)
                .zip(before)
                .map(|((&c, &b), &a)| u64::from(zigzag_residual(c, extrapolate(b, a), bits))),
        ),
    }
    stream::write(out, v);
}

/// `2 base - before`; [`zigzag_residual`] and [`apply_residual`] reduce it modulo `2^bits`.
#[inline]
fn extrapolate(base: u16, before: u16) -> u16 {
    base.wrapping_mul(2).wrapping_sub(before)
}

/// Reads the stream of one component of `n` codes of `bits` bits predicted by `predictor`
/// (`base` holds the base frame's codes for [`Predictor::Base`], and `before` the codes of the
/// frame before it as well for [`Predictor::Linear`]).
pub(crate) fn read(
    r: &mut Reader<'_>,
    n: usize,
    bits: u8,
    predictor: Predictor,
    (base, before): (Option<&[u16]>, Option<&[u16]>),
    values: &mut Vec<u64>,
) -> Result<Vec<u16>, DecodeError> {
    // The stream's width is at most `bits`, so every stored value fits in `bits` bits.
    stream::read(r, n, u32::from(bits), values)?;
    let mut codes: Vec<u16> = values.iter().map(|&v| v as u16).collect();
    match (predictor, base, before) {
        (Predictor::None, ..) => {}
        (Predictor::Previous, ..) => {
            let mut prev = 0;
            for c in &mut codes {
                prev = apply_residual(*c, prev, bits);
                *c = prev;
            }
        }
        (Predictor::Base, Some(base), _) if base.len() == n => {
            for (c, &b) in codes.iter_mut().zip(base) {
                *c = apply_residual(*c, b, bits);
            }
        }
        (Predictor::Linear, Some(base), Some(before)) if base.len() == n && before.len() == n => {
            for ((c, &b), &a) in codes.iter_mut().zip(base).zip(before) {
                *c = apply_residual(*c, extrapolate(b, a), bits);
            }
        }
        (p, ..) => return Err(DecodeError::malformed(format!("predictor {p:?} cannot apply to this channel"))),
    }
    Ok(codes)
}
