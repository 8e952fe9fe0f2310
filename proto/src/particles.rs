//! A copy of a particle set's state for output: positions plus named channels, in
//! identity order (index = particle id) when it comes from a simulation. The engine
//! produces it, the server encodes it into frames, clients rebuild it from frames,
//! and the writers in [`crate::export`] save it.

use crate::frame::Values;

/// Positions and named channels of one particle set.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Particles {
    /// The particle set they belong to (`particles` for a scene's SPH particles).
    pub set: String,
    /// Positions (m).
    pub positions: Vec<[f32; 3]>,
    /// Other channels by name (`velocity`, `density`, ...), one value per particle each.
    pub channels: Vec<(String, Values)>,
}

impl Particles {
    /// The values of channel `name`, if present.
    pub fn channel(&self, name: &str) -> Option<&Values> {
        self.channels.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// Every `k`-th particle (0, k, 2k, ...): the same particles in every frame, so
    /// identity-ordered streams of a decimated scene stay consistent.
    pub fn every(&self, k: usize) -> Particles {
        Particles {
            set: self.set.clone(),
            positions: self.positions.iter().step_by(k).copied().collect(),
            channels: self.channels.iter().map(|(n, v)| (n.clone(), v.every(k))).collect(),
        }
    }
}
