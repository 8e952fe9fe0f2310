//! A copy of a particle set's state for output: positions plus named channels, in
//! identity order (index = particle id) when it comes from a simulation. The engine
//! produces it, the server encodes it into frames, clients rebuild it from frames,
//! and the writers in [`crate::export`] save it. A grid (a module's field on
//! regular cells) travels the same way, with its cells' values as channels and no
//! positions.

use crate::frame::{GridInfo, Values};

/// Positions and named channels of one particle set.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Particles {
    /// The particle set they belong to (`particles` for a scene's SPH particles).
    pub set: String,
    /// Positions (m); empty for a grid.
    pub positions: Vec<[f32; 3]>,
    /// Other channels by name (`velocity`, `density`, ...), one value per particle
    /// (or cell, x fastest) each.
    pub channels: Vec<(String, Values)>,
    /// The cells, when the set is a grid.
    pub grid: Option<GridInfo>,
    /// The particles' stable ids, ascending, where they are not `0 .. n` (a set whose
    /// particles are born and die): particle `i` is `ids[i]`.
    pub ids: Option<Vec<u32>>,
}

impl Particles {
    /// The stable id of particle `i` (`i` itself where the set sends no ids).
    pub fn id(&self, i: usize) -> u32 {
        self.ids.as_ref().map_or(i as u32, |ids| ids[i])
    }

    /// The values of channel `name`, if present.
    pub fn channel(&self, name: &str) -> Option<&Values> {
        self.channels.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// Every `k`-th particle (0, k, 2k, ...): the same particles in every frame, so
    /// identity-ordered streams of a decimated scene stay consistent. A grid is
    /// always whole.
    pub fn every(&self, k: usize) -> Particles {
        if self.grid.is_some() {
            return self.clone();
        }
        Particles {
            set: self.set.clone(),
            positions: self.positions.iter().step_by(k).copied().collect(),
            channels: self.channels.iter().map(|(n, v)| (n.clone(), v.every(k))).collect(),
            grid: None,
            ids: self.ids.as_ref().map(|ids| ids.iter().step_by(k).copied().collect()),
        }
    }

    /// The particles `indices` (ascending), with their ids: a subset such as a region
    /// of interest, which identity-ordered frames name particle by particle. A grid is
    /// always whole.
    pub fn pick(&self, indices: &[u32]) -> Particles {
        if self.grid.is_some() {
            return self.clone();
        }
        Particles {
            set: self.set.clone(),
            positions: indices.iter().map(|&i| self.positions[i as usize]).collect(),
            channels: self.channels.iter().map(|(n, v)| (n.clone(), v.pick(indices))).collect(),
            grid: None,
            ids: Some(indices.iter().map(|&i| self.id(i as usize)).collect()),
        }
    }
}
