//! Particle data going into the encoder and coming out of the decoder.

use crate::header::Header;

/// What to encode: positions and any other channels, borrowed from the caller, all of
/// the same length (one entry per particle). A channel is in the frame only if it is given.
#[derive(Debug, Clone, Copy, Default)]
pub struct FrameInput<'a> {
    /// Positions (m).
    pub positions: &'a [[f32; 3]],
    /// Velocities (m/s).
    pub velocities: Option<&'a [[f32; 3]]>,
    /// Densities (kg/m^3).
    pub densities: Option<&'a [f32]>,
    /// Pressures (Pa).
    pub pressures: Option<&'a [f32]>,
    /// Temperatures (K).
    pub temperatures: Option<&'a [f32]>,
    /// Phase or material index per particle, sent exactly.
    pub phases: Option<&'a [u8]>,
}

impl<'a> FrameInput<'a> {
    /// Positions only.
    pub fn positions(positions: &'a [[f32; 3]]) -> Self {
        Self { positions, ..Self::default() }
    }
}

/// A decoded frame. Values are de-quantised: each is within the channel's `max_error`
/// (in the header's channel table) of what was encoded. In unordered frames particles
/// are in spatial (Morton) order, the same order in every channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The header and channel table.
    pub header: Header,
    /// Positions (m).
    pub positions: Vec<[f32; 3]>,
    /// Velocities (m/s), if sent.
    pub velocities: Option<Vec<[f32; 3]>>,
    /// Densities (kg/m^3), if sent.
    pub densities: Option<Vec<f32>>,
    /// Pressures (Pa), if sent.
    pub pressures: Option<Vec<f32>>,
    /// Temperatures (K), if sent.
    pub temperatures: Option<Vec<f32>>,
    /// Phase or material indices, if sent.
    pub phases: Option<Vec<u8>>,
}
