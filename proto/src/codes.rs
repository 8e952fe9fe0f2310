//! Channels as quantised codes: the form both modes predict and store, and the form
//! an identity-ordered encoder and decoder keep of the last frame to predict from.

use crate::error::EncodeError;
use crate::frame::{Frame, FrameInput};
use crate::header::{ChannelInfo, ChannelKind, ComponentRange};
use crate::quantize::{Quantizer, finite_range};

/// The raw u8 quantisation of the phase channel: codes are the values.
pub(crate) const PHASE: Quantizer = Quantizer { min: 0.0, max: 255.0, bits: 8 };

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
            .map(|q| {
                if self.kind == ChannelKind::Phase { ComponentRange { max_error: 0.0, ..q.range() } } else { q.range() }
            })
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

/// Bits for each channel other than positions.
pub(crate) struct ChannelBits {
    pub(crate) velocity: u8,
    pub(crate) density: u8,
    pub(crate) pressure: u8,
    pub(crate) temperature: u8,
}

/// Quantises every channel of `input`: positions over `position` (fixed bounds), the other
/// float channels over their own per-frame ranges, phases as raw codes. `reuse` hands back
/// code vectors of an earlier frame to fill, so steady streaming does not allocate.
pub(crate) fn quantise(
    input: &FrameInput<'_>,
    position: [Quantizer; 3],
    bits: &ChannelBits,
    reuse: &mut Vec<Vec<u16>>,
) -> Result<Vec<ChannelCodes>, EncodeError> {
    let mut fresh = || {
        let mut c = reuse.pop().unwrap_or_default();
        c.clear();
        c
    };
    let mut out = Vec::with_capacity(ChannelKind::ALL.len());
    let p = input.positions;
    let codes =
        vec![axis::<0>(p, &position, fresh()), axis::<1>(p, &position, fresh()), axis::<2>(p, &position, fresh())];
    out.push(ChannelCodes { kind: ChannelKind::Position, quantizers: position.to_vec(), codes });
    if let Some(v) = input.velocities {
        let (mut quantizers, mut codes) = (Vec::new(), Vec::new());
        for k in 0..3 {
            let q = per_frame(ChannelKind::Velocity, bits.velocity, v.iter().map(|x| x[k]))?;
            let mut c = fresh();
            q.encode_into(v.iter().map(|x| x[k]), &mut c);
            quantizers.push(q);
            codes.push(c);
        }
        out.push(ChannelCodes { kind: ChannelKind::Velocity, quantizers, codes });
    }
    let scalars = [
        (ChannelKind::Density, input.densities, bits.density),
        (ChannelKind::Pressure, input.pressures, bits.pressure),
        (ChannelKind::Temperature, input.temperatures, bits.temperature),
    ];
    for (kind, values, b) in scalars {
        if let Some(v) = values {
            let q = per_frame(kind, b, v.iter().copied())?;
            let mut c = fresh();
            q.encode_into(v.iter().copied(), &mut c);
            out.push(ChannelCodes { kind, quantizers: vec![q], codes: vec![c] });
        }
    }
    if let Some(v) = input.phases {
        let mut c = fresh();
        c.extend(v.iter().map(|&x| u16::from(x)));
        out.push(ChannelCodes { kind: ChannelKind::Phase, quantizers: vec![PHASE], codes: vec![c] });
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

/// De-quantises `codes` (one vector per component, all of length `n`) into the frame's field
/// for `kind`.
pub(crate) fn store(frame: &mut Frame, kind: ChannelKind, quantizers: &[Quantizer], codes: &[Vec<u16>]) {
    let scalar = || {
        let (q, c) = (quantizers[0], &codes[0]);
        let step = q.step();
        c.iter().map(|&x| q.min + f32::from(x) * step).collect::<Vec<f32>>()
    };
    let vector = || {
        let steps: Vec<f32> = quantizers.iter().map(Quantizer::step).collect();
        let mins: Vec<f32> = quantizers.iter().map(|q| q.min).collect();
        let (x, y, z) = (&codes[0], &codes[1], &codes[2]);
        x.iter()
            .zip(y)
            .zip(z)
            .map(|((&a, &b), &c)| {
                [
                    mins[0] + f32::from(a) * steps[0],
                    mins[1] + f32::from(b) * steps[1],
                    mins[2] + f32::from(c) * steps[2],
                ]
            })
            .collect::<Vec<[f32; 3]>>()
    };
    match kind {
        ChannelKind::Position => frame.positions = vector(),
        ChannelKind::Velocity => frame.velocities = Some(vector()),
        ChannelKind::Density => frame.densities = Some(scalar()),
        ChannelKind::Pressure => frame.pressures = Some(scalar()),
        ChannelKind::Temperature => frame.temperatures = Some(scalar()),
        ChannelKind::Phase => frame.phases = Some(codes[0].iter().map(|&c| c as u8).collect()),
    }
}
