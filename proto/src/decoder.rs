//! The decoder: checks a frame completely before trusting it, and keeps the last
//! identity-ordered frame to apply delta frames to.

use crate::channels::ChannelKind;
use crate::codes::{self, ChannelCodes};
use crate::error::DecodeError;
use crate::frame::{Frame, GridInfo};
use crate::header::{FIXED_HEADER_LEN, Header, MAGIC, MIN_VERSION, Mode, Predictor, VERSION};
use crate::predict;
use crate::reader::Reader;
use crate::unordered;

/// The most a caller accepts from one frame; frames declaring more are refused with
/// [`DecodeError::TooLarge`] before anything is allocated for them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most particles per frame.
    pub max_particles: u32,
    /// Most bytes per frame.
    pub max_frame_bytes: u32,
}

impl Default for Limits {
    /// 16 Mi particles and 1 GiB: far above what one scene streams, still a bound.
    fn default() -> Self {
        Self { max_particles: 1 << 24, max_frame_bytes: 1 << 30 }
    }
}

/// The identity-ordered frame a decoder holds.
#[derive(Debug, Clone)]
struct Base {
    scene_id: u64,
    sequence: u64,
    channels: Vec<ChannelCodes>,
    /// Position codes of the frame this one predicted from, if it was a delta frame.
    before: Option<Vec<Vec<u16>>>,
    /// The particles' ids, where the frame carried them.
    ids: Option<Vec<u32>>,
}

/// Decodes a stream of frames from one encoder.
#[derive(Debug, Clone, Default)]
pub struct Decoder {
    limits: Limits,
    last_sequence: Option<u64>,
    base: Option<Base>,
    /// Morton-key differences of the positions being read, reused from frame to frame.
    keys: Vec<u64>,
    /// Code vectors of frames no longer needed, reused so steady streaming does not allocate.
    spare_codes: Vec<Vec<u16>>,
}

impl Decoder {
    /// A decoder that refuses frames over `limits`.
    pub fn new(limits: Limits) -> Self {
        Self { limits, ..Self::default() }
    }

    /// Sequence number of the last frame decoded, of either mode.
    pub fn last_sequence(&self) -> Option<u64> {
        self.last_sequence
    }

    /// Sequence number of the identity-ordered frame delta frames can apply to.
    pub fn held_sequence(&self) -> Option<u64> {
        self.base.as_ref().map(|b| b.sequence)
    }

    /// Forgets the held frame, so only a keyframe decodes next.
    pub fn reset(&mut self) {
        self.base = None;
        self.last_sequence = None;
    }

    /// Decodes the frame at the start of `bytes` (bytes after its `frame_len` are not read).
    /// On any error the decoder's state is unchanged.
    pub fn decode(&mut self, bytes: &[u8]) -> Result<Frame, DecodeError> {
        let header = read_header(bytes, &self.limits)?;
        let frame = &bytes[..header.frame_len as usize];
        let n = header.particle_count as usize;
        let base = match (header.mode, header.keyframe) {
            (Mode::IdentityOrdered, false) => match &self.base {
                Some(b) if b.sequence == header.base_sequence && b.scene_id == header.scene_id => Some(b),
                held => {
                    return Err(DecodeError::NeedKeyframe {
                        sequence: header.sequence,
                        base: header.base_sequence,
                        held: held.as_ref().map(|b| b.sequence),
                    });
                }
            },
            _ => None,
        };
        let mut r = Reader::new(frame, "channel payloads");
        r.skip(header.encoded_len())?;
        let mut out =
            Frame { header: header.clone(), positions: Vec::new(), grid: None, channels: Vec::new(), ids: None };
        let mut kept = Vec::new();
        for (i, info) in header.channels.iter().enumerate() {
            let payload = r.take(info.payload_len as usize)?;
            let kind = info.kind();
            let mut p = Reader::new(payload, "channel payload");
            let quantizers = ChannelCodes::quantizers_of(info);
            let in_channel = |e: DecodeError| match e {
                DecodeError::Malformed { what } => DecodeError::malformed(format!("channel {i} ({kind}): {what}")),
                other => other,
            };
            if kind == ChannelKind::GRID {
                let dims = [p.u32()?, p.u32()?, p.u32()?];
                let r = &info.ranges;
                let grid = GridInfo {
                    origin: [r[0].min, r[1].min, r[2].min],
                    size: [r[0].max - r[0].min, r[1].max - r[1].min, r[2].max - r[2].min],
                    dims,
                };
                if grid.cells() != n as u64 {
                    return Err(in_channel(DecodeError::malformed(format!(
                        "cell counts {dims:?} do not make the frame's {n} cells"
                    ))));
                }
                out.grid = Some(grid);
            } else if kind == ChannelKind::IDS {
                out.ids = Some(read_ids(&mut p, n).map_err(in_channel)?);
            } else if info.predictor == Predictor::Morton {
                out.positions =
                    unordered::read_positions(&mut p, n, &quantizers, &mut self.keys).map_err(in_channel)?;
            } else {
                let prev = base.and_then(|b| b.channels.iter().find(|c| c.kind == kind));
                let before = base.and_then(|b| b.before.as_ref()).filter(|_| kind == ChannelKind::POSITION);
                let temporal = matches!(info.predictor, Predictor::Base | Predictor::Linear);
                if temporal && !prev.is_some_and(|c| c.same_quantisation(info)) {
                    return Err(DecodeError::malformed(format!(
                        "channel {i} ({kind}) predicts from frame {}, which quantised it differently or lacks it",
                        header.base_sequence
                    )));
                }
                if info.predictor == Predictor::Linear && before.is_none() {
                    return Err(DecodeError::malformed(format!(
                        "channel {i} ({kind}) extrapolates from frame {} and the one before, but that was a keyframe",
                        header.base_sequence
                    )));
                }
                let mut codes: Vec<Vec<u16>> =
                    (0..quantizers.len()).map(|_| self.spare_codes.pop().unwrap_or_default()).collect();
                let reference = |k: usize| (prev.map(|c| c.codes[k].as_slice()), before.map(|b| b[k].as_slice()));
                if let Err(e) = predict::read(&mut p, n, info.bits, info.predictor, reference, &mut codes) {
                    self.spare_codes.extend(codes);
                    return Err(in_channel(e));
                }
                if kind == ChannelKind::POSITION {
                    out.positions = codes::positions(&quantizers, &codes);
                } else {
                    out.channels.push((kind, codes::values(kind, &quantizers, &codes)));
                }
                match header.mode {
                    Mode::IdentityOrdered => kept.push(ChannelCodes { kind, quantizers, codes }),
                    Mode::Unordered | Mode::Grid => self.spare_codes.extend(codes),
                }
            }
            if p.remaining() != 0 {
                return Err(in_channel(DecodeError::malformed(format!("{} bytes left over", p.remaining()))));
            }
        }
        // A delta frame's particles are its base frame's.
        if let Some(b) = base
            && b.ids != out.ids
        {
            self.spare_codes.extend(kept.into_iter().flat_map(|ch| ch.codes));
            return Err(DecodeError::malformed(format!(
                "delta frame {} carries other particle ids than its base frame {}",
                header.sequence, header.base_sequence
            )));
        }
        if header.mode == Mode::IdentityOrdered {
            let delta = base.is_some();
            let before = match (delta, self.base.take()) {
                (true, Some(old)) => {
                    let mut channels = old.channels.into_iter();
                    let positions = channels.next().map(|p| p.codes);
                    self.spare_codes.extend(channels.flat_map(|ch| ch.codes).chain(old.before.into_iter().flatten()));
                    positions
                }
                (_, old) => {
                    let all = old.into_iter().flat_map(|b| {
                        b.channels.into_iter().flat_map(|ch| ch.codes).chain(b.before.into_iter().flatten())
                    });
                    self.spare_codes.extend(all);
                    None
                }
            };
            let ids = out.ids.clone();
            self.base =
                Some(Base { scene_id: header.scene_id, sequence: header.sequence, channels: kept, before, ids });
        }
        self.last_sequence = Some(header.sequence);
        Ok(out)
    }
}

/// Reads the ids channel's payload of `n` particles ([`Predictor::Gaps`]): ascending ids
/// of at most 32 bits.
fn read_ids(r: &mut Reader<'_>, n: usize) -> Result<Vec<u32>, DecodeError> {
    let mut gaps: Vec<u64> = Vec::new();
    crate::stream::read(r, n, 32, &mut gaps)?;
    let mut ids = Vec::with_capacity(n);
    let mut next = 0u64;
    for (k, gap) in gaps.into_iter().enumerate() {
        let id = next + gap;
        let id = u32::try_from(id).map_err(|_| DecodeError::malformed(format!("id {k} is {id}, beyond 32 bits")))?;
        ids.push(id);
        next = u64::from(id) + 1;
    }
    Ok(ids)
}

/// Reads and checks the header of the frame at the start of `bytes` without decoding its
/// payload: to learn a frame's length and contents, or to split a byte stream into frames.
pub fn read_header(bytes: &[u8], limits: &Limits) -> Result<Header, DecodeError> {
    let available = bytes.len();
    let prefix = available.min(MAGIC.len());
    if bytes[..prefix] != MAGIC[..prefix] {
        return Err(DecodeError::malformed("not a Floe frame (bad magic)"));
    }
    if available >= 6 {
        let found = u16::from_le_bytes([bytes[4], bytes[5]]);
        if !(MIN_VERSION..=VERSION).contains(&found) {
            return Err(DecodeError::UnsupportedVersion { found, oldest: MIN_VERSION, newest: VERSION });
        }
    }
    if available < FIXED_HEADER_LEN {
        return Err(DecodeError::Incomplete { needed: FIXED_HEADER_LEN, available });
    }
    let frame_len = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
    let particles = u32::from_le_bytes([bytes[12], bytes[13], bytes[14], bytes[15]]);
    if frame_len > limits.max_frame_bytes {
        let (declared, limit) = (u64::from(frame_len), u64::from(limits.max_frame_bytes));
        return Err(DecodeError::TooLarge { what: "bytes", declared, limit });
    }
    if particles > limits.max_particles {
        let (declared, limit) = (u64::from(particles), u64::from(limits.max_particles));
        return Err(DecodeError::TooLarge { what: "particles", declared, limit });
    }
    let frame_len = frame_len as usize;
    if frame_len < FIXED_HEADER_LEN {
        return Err(DecodeError::malformed(format!("frame length {frame_len} is shorter than the fixed header")));
    }
    if available < frame_len {
        return Err(DecodeError::Incomplete { needed: frame_len, available });
    }
    let header = Header::read(&bytes[..frame_len])?;
    check(&header)?;
    Ok(header)
}

/// Checks how the header's fields fit together: positions (or, in a grid frame, the grid)
/// first and once, every other channel at most once and with the table's component
/// count where the table defines it, predictors allowed by the mode, and lengths that
/// add up to the frame length.
fn check(h: &Header) -> Result<(), DecodeError> {
    let bad = |what: String| Err(DecodeError::malformed(what));
    let delta = h.mode == Mode::IdentityOrdered && !h.keyframe;
    if h.mode != Mode::IdentityOrdered && !h.keyframe {
        return bad("unordered and grid frames are all keyframes".into());
    }
    if h.mode == Mode::Grid && h.version < 4 {
        return bad(format!("grid frames need format version 4, not {}", h.version));
    }
    if let Some(i) = h.channels.iter().position(|c| c.kind() == ChannelKind::IDS)
        && (h.version < 5 || h.mode != Mode::IdentityOrdered || i + 1 != h.channels.len())
    {
        return bad(format!(
            "channel {i}: ids come last, in identity-ordered frames of version 5 (this one: {:?}, version {})",
            h.mode, h.version
        ));
    }
    if !delta && h.base_sequence != h.sequence {
        return bad(format!("keyframe {} names base frame {}", h.sequence, h.base_sequence));
    }
    if delta && h.base_sequence == h.sequence {
        return bad(format!("delta frame {} predicts from itself", h.sequence));
    }
    let first = if h.mode == Mode::Grid { ChannelKind::GRID } else { ChannelKind::POSITION };
    let mut total = h.encoded_len() as u64;
    for (i, c) in h.channels.iter().enumerate() {
        total += u64::from(c.payload_len);
        let kind = c.kind();
        if (i == 0) != (kind == first) || (i > 0 && (kind == ChannelKind::POSITION || kind == ChannelKind::GRID)) {
            return bad(format!("channel {i} is {kind}; {first} comes first and once"));
        }
        if h.channels[..i].iter().any(|o| o.tag == c.tag) {
            return bad(format!("channel {i}: a second {kind} channel"));
        }
        if let Some(def) = kind.def()
            && c.components != def.components
        {
            return bad(format!("channel {i}: {kind} has {} components, not {}", def.components, c.components));
        }
        if kind == ChannelKind::GRID && (c.payload_len, c.bits) != (12, 16) {
            return bad(format!(
                "channel {i}: the grid has 16 bits and 12 bytes, not {} and {}",
                c.bits, c.payload_len
            ));
        }
        let allowed: &[Predictor] = match (h.mode, kind, delta) {
            (_, ChannelKind::IDS, _) => &[Predictor::Gaps],
            (Mode::Grid, ChannelKind::GRID, _) => &[Predictor::None],
            (Mode::Grid, _, _) => &[Predictor::None, Predictor::Previous],
            (Mode::Unordered, ChannelKind::POSITION, _) => &[Predictor::Morton],
            (Mode::Unordered, _, _) => &[Predictor::None, Predictor::Previous],
            (Mode::IdentityOrdered, ChannelKind::POSITION, true) => &[Predictor::Base, Predictor::Linear],
            (Mode::IdentityOrdered, _, true) => &[Predictor::None, Predictor::Previous, Predictor::Base],
            (Mode::IdentityOrdered, _, false) => &[Predictor::None, Predictor::Previous],
        };
        if !allowed.contains(&c.predictor) {
            return bad(format!("channel {i}: predictor {:?} is not allowed for {kind} in this frame", c.predictor));
        }
    }
    if total != u64::from(h.frame_len) {
        return bad(format!("header and payloads add up to {total} bytes, but the frame length is {}", h.frame_len));
    }
    Ok(())
}
