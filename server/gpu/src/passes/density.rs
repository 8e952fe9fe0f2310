//! Density and `p / rho^2` per particle (see density.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of density.wgsl.
pub const SOURCE: &str = super::particle_kernel!("density.wgsl");

/// params, positions, cell starts, walls, wall cell starts, (rho, p/rho^2).
const BINDINGS: &[(u32, Access)] = &[(0, U), (1, R), (2, R), (3, R), (4, R), (5, W)];

/// The density pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "density.wgsl", SOURCE, "density", BINDINGS)
}
