//! The guard's and time step's reduction (see measure.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of measure.wgsl.
pub const SOURCE: &str = super::particle_kernel!("measure.wgsl");

/// Particles per partial (the reduction's workgroup size).
pub const PER_PARTIAL: u32 = 256;

const BINDINGS: &[(u32, Access)] = &[(0, U), (1, R), (2, R), (3, R), (4, R), (5, W)];

/// params, positions, velocities, accelerations, (rho, p/rho^2), partials.
#[derive(Debug)]
pub struct Measure {
    pub partials: Kernel,
    /// One workgroup: reduces the partials into the first.
    pub total: Kernel,
}

impl Measure {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "measure.wgsl", SOURCE);
        let layout = Layout::new(device, "measure", BINDINGS);
        Self {
            partials: Kernel::new(device, &m, "measure partials", "partials", &layout, PER_PARTIAL),
            total: Kernel::new(device, &m, "measure total", "total", &layout, PER_PARTIAL),
        }
    }
}
