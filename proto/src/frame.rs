//! Particle data going into the encoder and coming out of the decoder.

use crate::channels::ChannelKind;
use crate::header::Header;

/// One channel's values for every particle (or grid cell): floats with a fixed number
/// of components per particle, interleaved (`x0 y0 z0 x1 y1 z1 ...`), or raw u8 values
/// for exact channels (material indices).
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Float values, `components` per particle.
    Float {
        /// Components per particle (1 to 4).
        components: u8,
        /// `components * n` values, particle by particle.
        data: Vec<f32>,
    },
    /// Raw u8 values, one per particle, sent exactly.
    Exact(Vec<u8>),
}

impl Values {
    /// One float per particle.
    pub fn scalars(data: Vec<f32>) -> Self {
        Values::Float { components: 1, data }
    }

    /// Three floats per particle.
    pub fn vectors(data: Vec<[f32; 3]>) -> Self {
        Values::Float { components: 3, data: data.into_flattened() }
    }

    /// Components per particle.
    pub fn components(&self) -> u8 {
        match self {
            Values::Float { components, .. } => *components,
            Values::Exact(_) => 1,
        }
    }

    /// Particles (or cells) the values cover.
    pub fn len(&self) -> usize {
        match self {
            Values::Float { components, data } => data.len() / usize::from((*components).max(1)),
            Values::Exact(v) => v.len(),
        }
    }

    /// Whether there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The floats of a one-component channel.
    pub fn as_scalars(&self) -> Option<&[f32]> {
        match self {
            Values::Float { components: 1, data } => Some(data),
            _ => None,
        }
    }

    /// The floats of a three-component channel, one array per particle.
    pub fn as_vectors(&self) -> Option<&[[f32; 3]]> {
        match self {
            Values::Float { components: 3, data } => Some(data.as_chunks::<3>().0),
            _ => None,
        }
    }

    /// The raw values of an exact channel.
    pub fn as_exact(&self) -> Option<&[u8]> {
        match self {
            Values::Exact(v) => Some(v),
            Values::Float { .. } => None,
        }
    }

    /// Particle `i`'s components as floats.
    pub fn get(&self, i: usize) -> Vec<f32> {
        match self {
            Values::Float { components, data } => {
                let c = usize::from(*components);
                data[c * i..c * (i + 1)].to_vec()
            }
            Values::Exact(v) => vec![f32::from(v[i])],
        }
    }

    /// Borrowed, for the encoder.
    pub fn as_ref(&self) -> ValuesRef<'_> {
        match self {
            Values::Float { components, data } => ValuesRef::Float { components: *components, data },
            Values::Exact(v) => ValuesRef::Exact(v),
        }
    }

    /// Every `k`-th particle's values (0, k, 2k, ...).
    pub fn every(&self, k: usize) -> Values {
        match self {
            Values::Float { components, data } => {
                let c = usize::from(*components);
                Values::Float {
                    components: *components,
                    data: data.chunks_exact(c).step_by(k).flatten().copied().collect(),
                }
            }
            Values::Exact(v) => Values::Exact(v.iter().step_by(k).copied().collect()),
        }
    }

    /// The values of the particles `indices` (in that order).
    pub fn pick(&self, indices: &[u32]) -> Values {
        match self {
            Values::Float { components, data } => {
                let c = usize::from(*components);
                let data = indices.iter().flat_map(|&i| &data[c * i as usize..c * (i as usize + 1)]).copied().collect();
                Values::Float { components: *components, data }
            }
            Values::Exact(v) => Values::Exact(indices.iter().map(|&i| v[i as usize]).collect()),
        }
    }
}

/// [`Values`] borrowed from the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ValuesRef<'a> {
    /// Float values, `components` per particle, interleaved.
    Float {
        /// Components per particle (1 to 4).
        components: u8,
        /// `components * n` values.
        data: &'a [f32],
    },
    /// Raw u8 values, one per particle.
    Exact(&'a [u8]),
}

impl ValuesRef<'_> {
    /// Components per particle.
    pub fn components(&self) -> u8 {
        match self {
            ValuesRef::Float { components, .. } => *components,
            ValuesRef::Exact(_) => 1,
        }
    }

    /// Particles the values cover (`None` when the float count is not a multiple of the
    /// component count).
    pub fn particles(&self) -> Option<usize> {
        match self {
            ValuesRef::Float { components, data } => {
                let c = usize::from(*components).max(1);
                (data.len() % c == 0).then_some(data.len() / c)
            }
            ValuesRef::Exact(v) => Some(v.len()),
        }
    }
}

/// A regular grid of cells: what a grid frame carries instead of particle positions.
/// Cells are numbered x fastest, then y, then z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridInfo {
    /// Lower corner (m).
    pub origin: [f32; 3],
    /// Extent per axis (m).
    pub size: [f32; 3],
    /// Cells per axis (each at least 1).
    pub dims: [u32; 3],
}

impl GridInfo {
    /// Number of cells.
    pub fn cells(&self) -> u64 {
        self.dims.iter().map(|&d| u64::from(d)).product()
    }
}

/// What to encode, borrowed from the caller: positions (or, for a grid frame, the grid)
/// and any other channels, all with one entry per particle (or cell). A channel is in
/// the frame only if it is given.
#[derive(Debug, Clone, Default)]
pub struct FrameInput<'a> {
    /// Positions (m); empty for a grid frame.
    pub positions: &'a [[f32; 3]],
    /// The grid, for a grid frame (the encoder's mode is then [`crate::Mode::Grid`]).
    pub grid: Option<GridInfo>,
    /// Which of the scene's particle sets (or grids) the frame carries.
    pub set: u8,
    /// Other channels, each at most once.
    pub channels: Vec<(ChannelKind, ValuesRef<'a>)>,
    /// The particles' stable ids, ascending, for an identity-ordered frame of a set whose
    /// particles are born and die (their ids are then not `0 .. n`).
    pub ids: Option<&'a [u32]>,
}

impl<'a> FrameInput<'a> {
    /// Positions only, of set 0.
    pub fn positions(positions: &'a [[f32; 3]]) -> Self {
        Self { positions, ..Self::default() }
    }

    /// Adds a channel.
    pub fn with(mut self, kind: ChannelKind, values: ValuesRef<'a>) -> Self {
        self.channels.push((kind, values));
        self
    }
}

/// A decoded frame. Values are de-quantised: each is within the channel's `max_error`
/// (in the header's channel table) of what was encoded. In unordered frames particles
/// are in spatial (Morton) order, the same order in every channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The header and channel table.
    pub header: Header,
    /// Positions (m); empty in a grid frame.
    pub positions: Vec<[f32; 3]>,
    /// The grid of a grid frame.
    pub grid: Option<GridInfo>,
    /// The other channels, in the frame's order.
    pub channels: Vec<(ChannelKind, Values)>,
    /// The particles' stable ids, ascending, where the frame carries them (identity-ordered
    /// frames of a set whose particles are born and die); particle `i` is then `ids[i]`.
    pub ids: Option<Vec<u32>>,
}

impl Frame {
    /// The values of channel `kind`, if the frame carries it.
    pub fn channel(&self, kind: ChannelKind) -> Option<&Values> {
        self.channels.iter().find(|(k, _)| *k == kind).map(|(_, v)| v)
    }

    /// The values of the channel the table names `name`, if the frame carries it.
    pub fn named(&self, name: &str) -> Option<&Values> {
        ChannelKind::named(name).and_then(|k| self.channel(k))
    }
}
