//! The encoder: turns particle data into frames, one stream per encoder.

use crate::channels::ChannelKind;
use crate::codes::{self, ChannelCodes};
use crate::error::EncodeError;
use crate::frame::{FrameInput, GridInfo, ValuesRef};
use crate::header::{ChannelInfo, ComponentRange, FIXED_HEADER_LEN, Header, Mode, Predictor, VERSION};
use crate::predict::{self, Reference};
use crate::quantize::Quantizer;
use crate::unordered;

/// Bits of a float channel the table does not define.
const DEFAULT_BITS: u8 = 10;

/// The box positions are quantised over (m). Particles outside it are clamped to its faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lowest corner (m).
    pub min: [f32; 3],
    /// Highest corner (m).
    pub max: [f32; 3],
}

impl Bounds {
    /// The box grown by `margin` (m) on every side, for particles that splash past the walls.
    pub fn with_margin(self, margin: f32) -> Self {
        Self { min: self.min.map(|v| v - margin), max: self.max.map(|v| v + margin) }
    }
}

/// How an encoder quantises and predicts.
#[derive(Debug, Clone, PartialEq)]
pub struct EncoderConfig {
    /// Unordered (viewers) or identity-ordered (clients that follow particles).
    pub mode: Mode,
    /// Written into every frame, so a decoder can tell streams of different scenes apart.
    pub scene_id: u64,
    /// Position quantisation box (m): the scene bounds with a margin. Its longest side sets
    /// the quantisation step of all three axes.
    pub bounds: Bounds,
    /// Bits per position axis, 8 to 16. All three axes share one step, the longest axis's
    /// span over `2^bits - 1`: at 16 bits over a 2 m box the error is 15 µm in every direction.
    pub position_bits: u8,
    /// Bits per component of other float channels, over the frame's own range (1 to 16),
    /// where they differ from the channel table's default (10 for channels it lacks).
    pub channel_bits: Vec<(ChannelKind, u8)>,
    /// Identity-ordered mode: a keyframe at least every this many frames (1 = all keyframes),
    /// so a client that joins or loses a frame waits at most this long.
    pub keyframe_interval: u32,
}

impl EncoderConfig {
    /// 16-bit positions, the table's bits for other channels (10 bits, 0.05 % of the
    /// frame's range, finer than a colour map shows), a keyframe every 30 frames (half a
    /// second at 60 frames/s).
    pub fn new(mode: Mode, scene_id: u64, bounds: Bounds) -> Self {
        Self { mode, scene_id, bounds, position_bits: 16, channel_bits: Vec::new(), keyframe_interval: 30 }
    }

    /// Bits per component of channel `kind`.
    pub fn bits(&self, kind: ChannelKind) -> u8 {
        match self.channel_bits.iter().find(|(k, _)| *k == kind) {
            Some(&(_, b)) => b,
            None => kind.def().map_or(DEFAULT_BITS, |d| d.bits),
        }
    }

    fn check(&self) -> Result<(), EncodeError> {
        let bad = |what: String| Err(EncodeError::InvalidConfig(what));
        if !(8..=16).contains(&self.position_bits) {
            return bad(format!("position_bits = {} (8 to 16 allowed)", self.position_bits));
        }
        for &(kind, b) in &self.channel_bits {
            if !(1..=16).contains(&b) {
                return bad(format!("{kind} bits = {b} (1 to 16 allowed)"));
            }
        }
        let Bounds { min, max } = self.bounds;
        for k in 0..3 {
            if !(min[k].is_finite() && max[k].is_finite() && min[k] <= max[k]) {
                return bad(format!("bounds axis {k}: [{}, {}] is not a finite, ordered range", min[k], max[k]));
            }
        }
        if self.position_quantizers().iter().any(|q| !(q.max.is_finite() && q.step().is_finite())) {
            return bad(format!("bounds {min:?} to {max:?} are too large for f32 steps"));
        }
        if self.keyframe_interval == 0 {
            return bad("keyframe_interval = 0 (at least 1)".into());
        }
        Ok(())
    }

    /// How positions are quantised. One step for all three axes, the longest axis's: each
    /// axis's range starts at the bounds' minimum and spans the longest axis. The error bound
    /// is then the same in every direction, and the shorter axes use fewer codes, which the
    /// streams store in fewer bits (0.4 bytes/particle less on the dam break's
    /// 2.2 x 1.3 x 0.35 m box).
    pub fn position_quantizers(&self) -> [Quantizer; 3] {
        let Bounds { min, max } = self.bounds;
        let span = (0..3).map(|k| max[k] - min[k]).fold(0.0, f32::max);
        std::array::from_fn(|k| Quantizer { min: min[k], max: min[k] + span, bits: self.position_bits })
    }
}

/// The last identity-ordered frame, which the next delta frame predicts from.
#[derive(Debug)]
struct Base {
    sequence: u64,
    channels: Vec<ChannelCodes>,
    /// The particles' ids, where the frame carried them: a delta frame needs the same.
    ids: Option<Vec<u32>>,
    /// Position codes of the frame this one predicted from, if it was a delta frame
    /// (a decoder then holds them too), for [`Predictor::Linear`].
    before: Option<Vec<Vec<u16>>>,
}

impl Base {
    fn particles(&self) -> usize {
        self.channels[0].codes[0].len()
    }
}

/// Encodes a stream of frames. Sequence numbers count up from 0; in identity-ordered mode
/// the encoder keeps the last frame's codes to predict the next one from.
#[derive(Debug)]
pub struct Encoder {
    config: EncoderConfig,
    next_sequence: u64,
    since_keyframe: u32,
    force_keyframe: bool,
    base: Option<Base>,
    spare_codes: Vec<Vec<u16>>,
    predict: predict::Scratch,
    unordered: unordered::Scratch,
}

impl Encoder {
    /// An encoder with a checked configuration.
    pub fn new(config: EncoderConfig) -> Result<Self, EncodeError> {
        config.check()?;
        Ok(Self {
            config,
            next_sequence: 0,
            since_keyframe: 0,
            force_keyframe: false,
            base: None,
            spare_codes: Vec::new(),
            predict: predict::Scratch::default(),
            unordered: unordered::Scratch::default(),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &EncoderConfig {
        &self.config
    }

    /// Sequence number the next frame gets.
    pub fn next_sequence(&self) -> u64 {
        self.next_sequence
    }

    /// Makes the next frame a keyframe (for a new subscriber, or one that lost a frame).
    pub fn force_keyframe(&mut self) {
        self.force_keyframe = true;
    }

    /// Encodes one frame taken at simulation `step` and time `time` (s).
    pub fn encode(&mut self, step: u64, time: f64, input: &FrameInput<'_>) -> Result<Vec<u8>, EncodeError> {
        let mut out = Vec::new();
        self.encode_into(step, time, input, &mut out)?;
        Ok(out)
    }

    /// Like [`Encoder::encode`], into `out` (cleared first), so its allocation is reused.
    pub fn encode_into(
        &mut self,
        step: u64,
        time: f64,
        input: &FrameInput<'_>,
        out: &mut Vec<u8>,
    ) -> Result<(), EncodeError> {
        let n = check_input(input, self.config.mode)?;
        if !time.is_finite() {
            return Err(EncodeError::NonFiniteTime(time));
        }
        let c = &self.config;
        let base = match self.base.take() {
            Some(b)
                if !self.force_keyframe
                    && self.since_keyframe < c.keyframe_interval
                    && b.particles() == n
                    && b.ids.as_deref() == input.ids =>
            {
                Some(b)
            }
            Some(b) => {
                self.spare_codes.extend(b.channels.into_iter().flat_map(|ch| ch.codes));
                None
            }
            None => None,
        };
        let position = (c.mode != Mode::Grid).then(|| c.position_quantizers());
        let channels = codes::quantise(input, position, |k| c.bits(k), &mut self.spare_codes)?;
        let sequence = self.next_sequence;
        let keyframe = base.is_none();

        out.clear();
        let mut header = Header {
            version: VERSION,
            mode: self.config.mode,
            keyframe,
            frame_len: 0,
            particle_count: n as u32,
            scene_id: self.config.scene_id,
            set: input.set,
            sequence,
            base_sequence: base.as_ref().map_or(sequence, |b| b.sequence),
            step,
            time,
            channels: Vec::with_capacity(channels.len()),
        };
        let grid_entry = input.grid.map_or(0, |_| 8 + 12 * 3);
        let ids_entry = input.ids.map_or(0, |_| 8 + 12);
        let header_len = FIXED_HEADER_LEN
            + grid_entry
            + ids_entry
            + channels.iter().map(|ch| 8 + 12 * ch.codes.len()).sum::<usize>();
        out.resize(header_len, 0);
        if let Some(grid) = input.grid {
            header.channels.push(write_grid(out, &grid));
        }
        // Positions of a delta frame extrapolate from the last two frames when the decoder
        // holds both, that is when the base frame was itself a delta frame.
        let linear = base.as_ref().and_then(|b| b.before.as_ref().map(|before| (&b.channels[0], before)));
        for (i, ch) in channels.iter().enumerate() {
            let at = out.len();
            let predictor = match (self.config.mode, i, linear) {
                (Mode::Grid, _, _) => {
                    predict::write(out, &ch.codes, ch.bits(), |_| Reference::Previous(None), &mut self.predict)
                }
                (Mode::Unordered, 0, _) => {
                    unordered::write_positions(out, ch, channels.len() > 1, &mut self.unordered);
                    Predictor::Morton
                }
                (Mode::Unordered, _, _) => {
                    let order = Some(self.unordered.ids.as_slice());
                    predict::write(out, &ch.codes, ch.bits(), |_| Reference::Previous(order), &mut self.predict)
                }
                (Mode::IdentityOrdered, 0, Some((p, before))) => predict::write(
                    out,
                    &ch.codes,
                    ch.bits(),
                    |k| Reference::Linear(&p.codes[k], &before[k]),
                    &mut self.predict,
                ),
                (Mode::IdentityOrdered, _, _) => {
                    let same = base.as_ref().and_then(|b| b.channels.iter().find(|p| p.quantised_like(ch)));
                    match same {
                        Some(p) => predict::write(
                            out,
                            &ch.codes,
                            ch.bits(),
                            |k| Reference::Base(&p.codes[k]),
                            &mut self.predict,
                        ),
                        // Particles created on a lattice keep neighbours at neighbouring
                        // indices, so the previous particle predicts a keyframe's positions
                        // (5.5 to 3.9 bytes/particle on the dam break) and other channels.
                        None => {
                            predict::write(out, &ch.codes, ch.bits(), |_| Reference::Previous(None), &mut self.predict)
                        }
                    }
                }
            };
            let payload_len = u32::try_from(out.len() - at).map_err(|_| EncodeError::FrameTooLarge)?;
            header.channels.push(ChannelInfo {
                tag: ch.kind.tag(),
                components: ch.codes.len() as u8,
                bits: ch.bits(),
                predictor,
                payload_len,
                ranges: ch.ranges(),
            });
        }
        if let Some(ids) = input.ids {
            header.channels.push(write_ids(out, ids)?);
        }
        header.frame_len = u32::try_from(out.len()).map_err(|_| EncodeError::FrameTooLarge)?;
        let mut head = Vec::with_capacity(header_len);
        header.write(&mut head);
        out[..header_len].copy_from_slice(&head);

        self.next_sequence += 1;
        self.force_keyframe = false;
        self.since_keyframe = if keyframe { 1 } else { self.since_keyframe + 1 };
        match self.config.mode {
            Mode::IdentityOrdered => {
                let before = base.map(|b| {
                    let mut old = b.channels.into_iter();
                    let positions = old.next().map(|p| p.codes).unwrap_or_default();
                    self.spare_codes.extend(old.flat_map(|ch| ch.codes).chain(b.before.into_iter().flatten()));
                    positions
                });
                self.base = Some(Base { sequence, channels, before, ids: input.ids.map(<[u32]>::to_vec) });
            }
            Mode::Unordered | Mode::Grid => self.spare_codes.extend(channels.into_iter().flat_map(|ch| ch.codes)),
        }
        Ok(())
    }
}

/// Appends the ids channel's payload (the gaps of ascending `ids`, [`Predictor::Gaps`])
/// and returns its table entry.
fn write_ids(out: &mut Vec<u8>, ids: &[u32]) -> Result<ChannelInfo, EncodeError> {
    let at = out.len();
    let mut prev: Option<u32> = None;
    let gaps: Vec<u64> = ids
        .iter()
        .map(|&id| {
            let gap = prev.map_or(u64::from(id), |p| u64::from(id - p - 1));
            prev = Some(id);
            gap
        })
        .collect();
    crate::stream::write(out, &gaps);
    let (first, last) = (ids.first().copied().unwrap_or(0), ids.last().copied().unwrap_or(0));
    Ok(ChannelInfo {
        tag: ChannelKind::IDS.tag(),
        components: 1,
        bits: 16,
        predictor: Predictor::Gaps,
        payload_len: u32::try_from(out.len() - at).map_err(|_| EncodeError::FrameTooLarge)?,
        ranges: vec![ComponentRange { min: first as f32, max: last as f32, max_error: 0.0 }],
    })
}

/// Appends the grid channel's payload (the cell counts) and returns its table entry.
fn write_grid(out: &mut Vec<u8>, grid: &GridInfo) -> ChannelInfo {
    for d in grid.dims {
        out.extend_from_slice(&d.to_le_bytes());
    }
    let ranges = (0..3)
        .map(|k| ComponentRange { min: grid.origin[k], max: grid.origin[k] + grid.size[k], max_error: 0.0 })
        .collect();
    ChannelInfo {
        tag: ChannelKind::GRID.tag(),
        components: 3,
        bits: 16,
        predictor: Predictor::None,
        payload_len: 12,
        ranges,
    }
}

/// Checks the input against the mode: positions or a grid, every channel once, with
/// the table's component count and form, one value per particle or cell. Returns the
/// particle (or cell) count.
fn check_input(input: &FrameInput<'_>, mode: Mode) -> Result<usize, EncodeError> {
    let bad = |what: String| Err(EncodeError::InvalidInput(what));
    let n = match (mode, &input.grid) {
        (Mode::Grid, Some(g)) => {
            if !input.positions.is_empty() {
                return bad("a grid frame has no positions".into());
            }
            if g.dims.contains(&0) || (0..3).any(|k| !(g.origin[k].is_finite() && g.size[k].is_finite())) {
                return bad(format!("grid {g:?}: dims at least 1, finite origin and size"));
            }
            usize::try_from(g.cells()).map_err(|_| EncodeError::TooManyParticles { count: usize::MAX })?
        }
        (Mode::Grid, None) => return bad("a grid frame needs a grid".into()),
        (_, Some(_)) => return bad("only grid frames carry a grid".into()),
        (_, None) => input.positions.len(),
    };
    if u32::try_from(n).is_err() {
        return Err(EncodeError::TooManyParticles { count: n });
    }
    if let Some(ids) = input.ids {
        if mode != Mode::IdentityOrdered {
            return bad("only identity-ordered frames carry ids".into());
        }
        if ids.len() != n {
            return bad(format!("{} ids for {n} particles", ids.len()));
        }
        if let Some(w) = ids.windows(2).find(|w| w[0] >= w[1]) {
            return bad(format!("ids must ascend: {} then {}", w[0], w[1]));
        }
    }
    if 1 + input.channels.len() + usize::from(input.ids.is_some()) > crate::header::MAX_CHANNELS {
        return bad(format!(
            "{} channels, at most {} besides the first",
            input.channels.len(),
            crate::header::MAX_CHANNELS - 1
        ));
    }
    for (i, &(kind, values)) in input.channels.iter().enumerate() {
        if input.channels[..i].iter().any(|(k, _)| *k == kind) {
            return bad(format!("{kind} is given twice"));
        }
        let (exact, components) = match (kind.def(), values) {
            (Some(d), _) if kind == ChannelKind::POSITION || kind == ChannelKind::GRID || kind == ChannelKind::IDS => {
                return bad(format!("{} is not a channel to give", d.name));
            }
            (Some(d), _) => (d.exact, d.components),
            (None, _) if !kind.is_dynamic() => return bad(format!("tag {} is not in the channel table", kind.tag())),
            (None, v) => (false, v.components()),
        };
        match values {
            ValuesRef::Exact(_) if !exact => return bad(format!("{kind} takes floats, not raw u8 values")),
            ValuesRef::Float { .. } if exact => return bad(format!("{kind} takes raw u8 values")),
            _ => {}
        }
        if values.components() != components || !(1..=4).contains(&components) {
            return bad(format!("{kind} has {components} components, given {}", values.components()));
        }
        match values.particles() {
            Some(got) if got == n => {}
            got => return Err(EncodeError::LengthMismatch { channel: kind, expected: n, got: got.unwrap_or(0) }),
        }
    }
    Ok(n)
}
