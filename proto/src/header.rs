//! The frame header and channel table: what a frame holds and how to read its payload.
//!
//! Every multi-byte field is little-endian; floats are IEEE 754. A frame is the fixed
//! header, then one channel-table entry per channel, then each channel's payload in
//! table order. A decoder in another language (the browser viewer's JavaScript) reads
//! the same layout; `proto/testdata/` holds frames to test it against.
//!
//! Fixed header (64 bytes):
//!
//! | offset | size | type | field |
//! |---:|---:|---|---|
//! | 0 | 4 | bytes | magic `FLOF` (`46 4C 4F 46`) |
//! | 4 | 2 | u16 | format version, [`VERSION`] |
//! | 6 | 1 | u8 | mode: 0 unordered, 1 identity-ordered ([`Mode`]) |
//! | 7 | 1 | u8 | flags: bit 0 keyframe; other bits zero |
//! | 8 | 4 | u32 | frame length in bytes, header included |
//! | 12 | 4 | u32 | particle count `n` |
//! | 16 | 8 | u64 | scene id |
//! | 24 | 8 | u64 | sequence number |
//! | 32 | 8 | u64 | base sequence: the frame an identity delta frame predicts from; else equal to the sequence |
//! | 40 | 8 | u64 | simulation step |
//! | 48 | 8 | f64 | simulated time (s) |
//! | 56 | 1 | u8 | channel count (1 to 16) |
//! | 57 | 1 | u8 | particle set: which of the scene's sets (or grids) the frame carries (version 4; zero in version 3) |
//! | 58 | 6 | | reserved, zero |
//!
//! Channel-table entry (`8 + 12 c` bytes for `c` components):
//!
//! | offset | size | type | field |
//! |---:|---:|---|---|
//! | 0 | 1 | u8 | kind tag ([`ChannelKind`], `proto/channels.json`); a tag the decoder's table lacks decodes as floats |
//! | 1 | 1 | u8 | component count `c` (1 to 4) |
//! | 2 | 1 | u8 | quantisation bits `b` (1 to 16) |
//! | 3 | 1 | u8 | predictor ([`Predictor`]) |
//! | 4 | 4 | u32 | payload length in bytes |
//! | 8 + 12 k | 4 | f32 | component k: range minimum |
//! | 12 + 12 k | 4 | f32 | component k: range maximum |
//! | 16 + 12 k | 4 | f32 | component k: maximum absolute error, half a quantisation step |
//!
//! The first channel is positions, or in a grid frame the grid (tag 6: its ranges are the grid's
//! extent per axis, its payload the three u32 cell counts). How payloads are laid out is in [`crate::stream`],
//! how values are quantised in [`crate::quantize`], and the predictors in [`Predictor`].

use crate::channels::ChannelKind;
use crate::error::DecodeError;
use crate::quantize::RangeForm;
use crate::reader::Reader;

/// Identifies a Floe frame: the first four bytes.
pub const MAGIC: [u8; 4] = *b"FLOF";
/// The format version this crate writes. Version 4 added the particle set byte, grid frames
/// and per-scene channel tags; version 5 the `ids` channel of identity-ordered frames whose
/// particles are born and die; version 3 and 4 frames still decode.
pub const VERSION: u16 = 5;
/// The oldest format version this crate reads.
pub const MIN_VERSION: u16 = 3;
/// Bytes of the fixed header, before the channel table.
pub const FIXED_HEADER_LEN: usize = 64;
/// Most channels a frame may declare, so a header's size stays bounded.
pub const MAX_CHANNELS: usize = 16;
/// Most components a channel may have.
pub const MAX_COMPONENTS: usize = 4;

/// Whether particle order carries identity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Mode {
    /// For viewers: particles arrive sorted spatially, so index `i` is not particle `i`;
    /// every frame stands alone.
    Unordered = 0,
    /// Index `i` is particle `i` in every frame; delta frames predict from the previous frame.
    IdentityOrdered = 1,
    /// A field on a regular grid (version 4): the first channel describes the grid, the
    /// others hold one value per cell, x fastest; every frame stands alone.
    Grid = 2,
}

impl Mode {
    fn from_tag(tag: u8) -> Option<Self> {
        match tag {
            0 => Some(Mode::Unordered),
            1 => Some(Mode::IdentityOrdered),
            2 => Some(Mode::Grid),
            _ => None,
        }
    }
}

/// How a channel's codes are predicted before they are stored; the stored values are
/// what the prediction missed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Predictor {
    /// The codes themselves.
    None = 0,
    /// Each code minus the previous particle's code in stream order, modulo `2^b`,
    /// zigzag-encoded (`0, -1, 1, -2, ...` as `0, 1, 2, 3, ...`); the first particle
    /// predicts from 0.
    Previous = 1,
    /// Each code minus the same particle's code in the base frame, modulo `2^b`, zigzag-encoded.
    /// Only in identity-ordered delta frames, and only when the base frame quantised the
    /// channel identically.
    Base = 2,
    /// Positions of unordered frames: the 3-axis Morton codes (x in bit 0, y in bit 1,
    /// z in bit 2 of each triple) sorted ascending, stored as differences from the previous
    /// code (the first from 0). Particles are in that sorted order in every channel.
    Morton = 3,
    /// Positions of identity-ordered delta frames whose base frame was itself a delta frame:
    /// each code minus its extrapolation `base + floor((g d + 2^11) / 2^12)` modulo 2^16, where
    /// `d` is `base - before` modulo 2^16 read as a signed 16-bit number (`before` is the base
    /// frame's own base), then modulo `2^b`, zigzag-encoded. The payload starts with each
    /// component's velocity gain `g`, an i16 in units of 2^-12, then the streams. The encoder
    /// fits `g` by least squares: 1 for equally spaced frames at constant velocity, the ratio
    /// of the intervals when frames are unequally spaced (a subscriber that skipped frames).
    /// Between frames 1/60 s apart the particles' motion changes far less than it moves, so
    /// these residuals are smaller than [`Predictor::Base`]'s (0.6 bytes/particle less on the
    /// dam break).
    Linear = 4,
    /// The `ids` channel (version 5): ascending u32 values stored as gaps, the first value
    /// and then each minus the one before it minus one, in one stream of at most 32 bits.
    Gaps = 5,
}

impl Predictor {
    fn from_tag(tag: u8) -> Option<Self> {
        match tag {
            0 => Some(Predictor::None),
            1 => Some(Predictor::Previous),
            2 => Some(Predictor::Base),
            3 => Some(Predictor::Morton),
            4 => Some(Predictor::Linear),
            5 => Some(Predictor::Gaps),
            _ => None,
        }
    }
}

/// The quantisation range of one component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComponentRange {
    /// Value of code 0.
    pub min: f32,
    /// Value of the largest code, `2^b - 1`.
    pub max: f32,
    /// Largest absolute error quantisation introduces: half a step, `(max - min) / (2^b - 1) / 2`
    /// in f32 (0 for the exact phase channel), in the channel's unit.
    pub max_error: f32,
}

/// One channel-table entry.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelInfo {
    /// Kind tag; [`ChannelInfo::kind`] gives the kind if this crate knows the tag.
    pub tag: u8,
    /// Components per particle.
    pub components: u8,
    /// Quantisation bits per component.
    pub bits: u8,
    /// How codes are predicted.
    pub predictor: Predictor,
    /// Bytes of this channel's payload.
    pub payload_len: u32,
    /// Quantisation range of each component.
    pub ranges: Vec<ComponentRange>,
}

impl ChannelInfo {
    /// The kind, if this crate knows the tag.
    pub fn kind(&self) -> ChannelKind {
        ChannelKind(self.tag)
    }

    /// Bytes of this entry in the channel table.
    pub fn table_len(&self) -> usize {
        8 + 12 * self.ranges.len()
    }
}

/// A decoded header: the fixed fields and the channel table.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// Format version.
    pub version: u16,
    /// Unordered or identity-ordered.
    pub mode: Mode,
    /// Whether the frame decodes on its own (always, for unordered frames).
    pub keyframe: bool,
    /// Bytes of the whole frame.
    pub frame_len: u32,
    /// Particles in the frame.
    pub particle_count: u32,
    /// Which scene the frame belongs to.
    pub scene_id: u64,
    /// Which of the scene's particle sets (or grids) the frame carries (0 in version 3).
    pub set: u8,
    /// Position of the frame in its encoder's stream.
    pub sequence: u64,
    /// The frame a delta frame predicts from (equal to `sequence` otherwise).
    pub base_sequence: u64,
    /// Simulation step the frame was taken at.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// The channels, positions first.
    pub channels: Vec<ChannelInfo>,
}

impl Header {
    /// Appends the header and channel table to `out`.
    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&MAGIC);
        out.extend_from_slice(&self.version.to_le_bytes());
        out.push(self.mode as u8);
        out.push(u8::from(self.keyframe));
        out.extend_from_slice(&self.frame_len.to_le_bytes());
        out.extend_from_slice(&self.particle_count.to_le_bytes());
        for v in [self.scene_id, self.sequence, self.base_sequence, self.step] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&self.time.to_le_bytes());
        // The encoder never builds more than MAX_CHANNELS channels.
        out.push(self.channels.len() as u8);
        out.push(self.set);
        out.extend_from_slice(&[0; 6]);
        for c in &self.channels {
            out.extend_from_slice(&[c.tag, c.components, c.bits, c.predictor as u8]);
            out.extend_from_slice(&c.payload_len.to_le_bytes());
            for r in &c.ranges {
                for v in [r.min, r.max, r.max_error] {
                    out.extend_from_slice(&v.to_le_bytes());
                }
            }
        }
    }

    /// Bytes of the header and channel table.
    pub fn encoded_len(&self) -> usize {
        FIXED_HEADER_LEN + self.channels.iter().map(ChannelInfo::table_len).sum::<usize>()
    }

    /// Reads the fixed header and the channel table from the start of a frame of exactly
    /// `frame.len()` bytes (the caller has checked the length field), checking each
    /// field on its own; the decoder then checks how the fields fit together.
    pub(crate) fn read(frame: &[u8]) -> Result<Header, DecodeError> {
        let mut r = Reader::new(frame, "header");
        r.skip(4)?;
        let version = r.u16()?;
        let mode_tag = r.u8()?;
        let mode =
            Mode::from_tag(mode_tag).ok_or_else(|| DecodeError::malformed(format!("unknown mode {mode_tag}")))?;
        let flags = r.u8()?;
        if flags & !1 != 0 {
            return Err(DecodeError::malformed(format!("reserved flag bits set: {flags:#04x}")));
        }
        let frame_len = r.u32()?;
        let particle_count = r.u32()?;
        let (scene_id, sequence, base_sequence, step) = (r.u64()?, r.u64()?, r.u64()?, r.u64()?);
        let time = r.f64()?;
        if !time.is_finite() {
            return Err(DecodeError::malformed(format!("time is {time}")));
        }
        let count = usize::from(r.u8()?);
        if !(1..=MAX_CHANNELS).contains(&count) {
            return Err(DecodeError::malformed(format!("{count} channels (1 to {MAX_CHANNELS} allowed)")));
        }
        let set = r.u8()?;
        if r.take(6)?.iter().any(|&b| b != 0) || (version < 4 && set != 0) {
            return Err(DecodeError::malformed("reserved header bytes are not zero"));
        }
        let mut channels = Vec::with_capacity(count);
        for i in 0..count {
            channels.push(read_channel(&mut r, i)?);
        }
        Ok(Header {
            version,
            mode,
            keyframe: flags & 1 != 0,
            frame_len,
            particle_count,
            scene_id,
            set,
            sequence,
            base_sequence,
            step,
            time,
            channels,
        })
    }
}

fn read_channel(r: &mut Reader<'_>, index: usize) -> Result<ChannelInfo, DecodeError> {
    let bad = |what: String| DecodeError::malformed(format!("channel {index}: {what}"));
    let [tag, components, bits, predictor_tag] = [r.u8()?, r.u8()?, r.u8()?, r.u8()?];
    if !(1..=MAX_COMPONENTS as u8).contains(&components) {
        return Err(bad(format!("{components} components (1 to {MAX_COMPONENTS} allowed)")));
    }
    if !(1..=16).contains(&bits) {
        return Err(bad(format!("{bits} quantisation bits (1 to 16 allowed)")));
    }
    let predictor =
        Predictor::from_tag(predictor_tag).ok_or_else(|| bad(format!("unknown predictor {predictor_tag}")))?;
    let payload_len = r.u32()?;
    let mut ranges = Vec::with_capacity(usize::from(components));
    for k in 0..components {
        let range = ComponentRange { min: r.f32()?, max: r.f32()?, max_error: r.f32()? };
        let form = match ChannelKind(tag) {
            ChannelKind::GRID | ChannelKind::IDS => RangeForm::Extent,
            k if k.exact() => RangeForm::ExactU8,
            _ => RangeForm::Quantised,
        };
        crate::quantize::check_range(&range, bits, form).map_err(|what| bad(format!("component {k}: {what}")))?;
        ranges.push(range);
    }
    Ok(ChannelInfo { tag, components, bits, predictor, payload_len, ranges })
}
