//! Channels as quantised codes: the form both modes predict and store, and the form
//! an identity-ordered encoder and decoder keep of the last frame to predict from.

use crate::channels::ChannelKind;
use crate::error::EncodeError;
use crate::frame::{FrameInput, Values, ValuesRef};
use crate::header::{ChannelInfo, ComponentRange};
use crate::quantize::{Quantizer, finite_range};

/// The raw u8 quantisation of exact channels: codes are the values.
pub(crate) const EXACT_U8: Quantizer = Quantizer { min: 0.0, max: 255.0, bits: 8 };

/// One channel's codes, one vector per component, and how they map back to values.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ChannelCodes {
    pub(crate) kind: ChannelKind,
    pub(crate) quantizers: Vec<Quantizer>,
    pub(crate) codes: Vec<Vec<u16>>,
}

impl ChannelCodes {
    /// Bits per code (the same for every component).
    pub(crate) fn bits(&self) -> u8 {
        self.quantizers[0].bits
    }

    /// Ranges as written in the channel table.
    pub(crate) fn ranges(&self) -> Vec<ComponentRange> {
        self.quantizers
            .iter()
            .map(|q| if self.kind.exact() { ComponentRange { max_error: 0.0, ..q.range() } } else { q.range() })
            .collect()
    }

    /// Whether `info` describes this channel quantised the same way (bit-identical ranges),
    /// so codes of the two frames can be subtracted.
    pub(crate) fn same_quantisation(&self, info: &ChannelInfo) -> bool {
        self.kind.tag() == info.tag
            && self.quantizers.len() == info.ranges.len()
            && self
                .quantizers
                .iter()
                .zip(&info.ranges)
                .all(|(q, r)| same_quantizer(q, &Quantizer { min: r.min, max: r.max, bits: info.bits }))
    }

    /// Whether `other` is the same channel quantised the same way (bit-identical ranges).
    pub(crate) fn quantised_like(&self, other: &ChannelCodes) -> bool {
        self.kind == other.kind
            && self.quantizers.len() == other.quantizers.len()
            && self.quantizers.iter().zip(&other.quantizers).all(|(a, b)| same_quantizer(a, b))
    }

    /// Quantisers of a channel described by `info`.
    pub(crate) fn quantizers_of(info: &ChannelInfo) -> Vec<Quantizer> {
        info.ranges.iter().map(|r| Quantizer { min: r.min, max: r.max, bits: info.bits }).collect()
    }
}

/// Equal bits and bit-identical range ends (so 0.0 and -0.0 differ, as their steps may).
fn same_quantizer(a: &Quantizer, b: &Quantizer) -> bool {
    a.bits == b.bits && a.min.to_bits() == b.min.to_bits() && a.max.to_bits() == b.max.to_bits()
}

/// Quantises `input`'s channels: positions over `position` (fixed bounds; grid frames have
/// none), the other float channels over their own per-frame ranges with `bits(kind)` bits,
/// exact channels as raw codes. `reuse` hands back code vectors of an earlier frame to fill,
/// so steady streaming does not allocate.
pub(crate) fn quantise(
    input: &FrameInput<'_>,
    position: Option<[Quantizer; 3]>,
    bits: impl Fn(ChannelKind) -> u8,
    reuse: &mut Vec<Vec<u16>>,
) -> Result<Vec<ChannelCodes>, EncodeError> {
    let mut fresh = || {
        let mut c = reuse.pop().unwrap_or_default();
        c.clear();
        c
    };
    let mut out = Vec::with_capacity(1 + input.channels.len());
    if let Some(position) = position {
        let p = input.positions;
        let codes =
            vec![axis::<0>(p, &position, fresh()), axis::<1>(p, &position, fresh()), axis::<2>(p, &position, fresh())];
        out.push(ChannelCodes { kind: ChannelKind::POSITION, quantizers: position.to_vec(), codes });
    }
    for &(kind, values) in &input.channels {
        match values {
            ValuesRef::Exact(v) => {
                let mut c = fresh();
                c.extend(v.iter().map(|&x| u16::from(x)));
                out.push(ChannelCodes { kind, quantizers: vec![EXACT_U8], codes: vec![c] });
            }
            ValuesRef::Float { components, data } => {
                let n = usize::from(components);
                let (mut quantizers, mut codes) = (Vec::with_capacity(n), Vec::with_capacity(n));
                for k in 0..n {
                    let component = || data.iter().skip(k).step_by(n).copied();
                    let q = per_frame(kind, bits(kind), component())?;
                    let mut c = fresh();
                    q.encode_into(component(), &mut c);
                    quantizers.push(q);
                    codes.push(c);
                }
                out.push(ChannelCodes { kind, quantizers, codes });
            }
        }
    }
    Ok(out)
}

/// Codes of axis `K` of `positions` appended to `out`. The axis is a constant, so the loop
/// reads a fixed offset of each position with no bounds check and is partly vectorised.
fn axis<const K: usize>(positions: &[[f32; 3]], quantizers: &[Quantizer; 3], mut out: Vec<u16>) -> Vec<u16> {
    let coder = quantizers[K].coder();
    out.extend(positions.iter().map(|v| coder.code(v[K])));
    out
}

/// The quantiser of one component over its per-frame range.
fn per_frame(kind: ChannelKind, bits: u8, values: impl Iterator<Item = f32>) -> Result<Quantizer, EncodeError> {
    let (min, max) = finite_range(values);
    let q = Quantizer { min, max, bits };
    if q.step().is_finite() { Ok(q) } else { Err(EncodeError::RangeOverflow { channel: kind }) }
}

/// De-quantises the codes of a position channel.
pub(crate) fn positions(quantizers: &[Quantizer], codes: &[Vec<u16>]) -> Vec<[f32; 3]> {
    let steps: Vec<f32> = quantizers.iter().map(Quantizer::step).collect();
    let mins: Vec<f32> = quantizers.iter().map(|q| q.min).collect();
    let (x, y, z) = (&codes[0], &codes[1], &codes[2]);
    x.iter()
        .zip(y)
        .zip(z)
        .map(|((&a, &b), &c)| {
            [mins[0] + f32::from(a) * steps[0], mins[1] + f32::from(b) * steps[1], mins[2] + f32::from(c) * steps[2]]
        })
        .collect()
}

/// De-quantises `codes` (one vector per component, all of length `n`) of a channel of
/// `kind` into its values, components interleaved.
pub(crate) fn values(kind: ChannelKind, quantizers: &[Quantizer], codes: &[Vec<u16>]) -> Values {
    if kind.exact() {
        return Values::Exact(codes[0].iter().map(|&c| c as u8).collect());
    }
    let components = quantizers.len();
    let n = codes.first().map_or(0, Vec::len);
    let mut data = vec![0.0f32; components * n];
    for (k, (q, c)) in quantizers.iter().zip(codes).enumerate() {
        let (min, step) = (q.min, q.step());
        for (slot, &code) in data.iter_mut().skip(k).step_by(components).zip(c) {
            *slot = min + f32::from(code) * step;
        }
    }
    Values::Float { components: components as u8, data }
}
