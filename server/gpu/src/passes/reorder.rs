//! Applying the sort's permutation to the state and the ids (see reorder.wgsl).

use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of reorder.wgsl.
pub const SOURCE: &str = super::particle_kernel!("reorder.wgsl");

const STATE: &[(u32, Access)] = &[(0, Access::Uniform), (1, Access::Read), (2, Access::Read), (3, Access::ReadWrite)];
const IDS: &[(u32, Access)] =
    &[(0, Access::Uniform), (1, Access::Read), (4, Access::Read), (5, Access::ReadWrite), (6, Access::ReadWrite)];

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
