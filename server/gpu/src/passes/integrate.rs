//! Kick and drift (see integrate.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of integrate.wgsl.
pub const SOURCE: &str = super::particle_kernel!("integrate.wgsl");

const BINDINGS: &[(u32, Access)] = &[(0, U), (1, U), (2, W), (3, W), (4, R), (5, R)];

/// params, step, positions, velocities, accelerations + XSPH, wall constraints.
#[derive(Debug)]
pub struct Integrate {
    pub kick: Kernel,
    pub drift: Kernel,
}

impl Integrate {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "integrate.wgsl", SOURCE);
        let layout = Layout::new(device, "integrate", BINDINGS);
        Self {
            kick: Kernel::new(device, &m, "kick", "kick", &layout, 128),
            drift: Kernel::new(device, &m, "drift", "drift", &layout, 128),
        }
    }
}
