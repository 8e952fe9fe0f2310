//! Applying the sort's permutation to the state and the ids (see reorder.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of reorder.wgsl.
pub const SOURCE: &str = super::particle_kernel!("reorder.wgsl");

const STATE: &[(u32, Access)] = &[(0, U), (1, R), (2, R), (3, W)];
const IDS: &[(u32, Access)] = &[(0, U), (1, R), (4, R), (5, W), (6, W)];

/// The two permutation kernels.
#[derive(Debug)]
pub struct Reorder {
    /// params, order, source vec4s, destination vec4s.
    pub state: Kernel,
    /// params, order, source ids, destination ids, slot of each id.
    pub ids: Kernel,
}

impl Reorder {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "reorder.wgsl", SOURCE);
        Self {
            state: Kernel::new(device, &m, "reorder state", "state", &Layout::new(device, "reorder state", STATE), 128),
            ids: Kernel::new(device, &m, "reorder ids", "ids", &Layout::new(device, "reorder ids", IDS), 128),
        }
    }
}
