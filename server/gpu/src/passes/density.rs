//! Density and `p / rho^2` per particle (see density.wgsl).

use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

const BINDINGS: &[(u32, Access)] = &[
    (0, Access::Uniform),
    (1, Access::Read),
    (2, Access::Read),
    (3, Access::Read),
    (4, Access::Read),
    (5, Access::ReadWrite),
];

/// Source of density.wgsl.
pub const SOURCE: &str = super::particle_kernel!("density.wgsl");

/// params, positions, cell starts, walls, wall cell starts, (rho, p/rho^2).
#[derive(Debug)]
pub struct Density {
    pub kernel: Kernel,
}

impl Density {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "density.wgsl", SOURCE);
        Self { kernel: Kernel::new(device, &m, "density", "main", &Layout::new(device, "density", BINDINGS), 128) }
    }
}
