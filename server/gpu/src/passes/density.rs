//! Density and `p / rho^2` per particle (see density.wgsl).

use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of density.wgsl.
pub const SOURCE: &str = super::particle_kernel!("density.wgsl");

/// params, positions, cell starts, walls, wall cell starts, (rho, p/rho^2).
const BINDINGS: &[(u32, Access)] = &[
    (0, Access::Uniform),
    (1, Access::Read),
    (2, Access::Read),
    (3, Access::Read),
    (4, Access::Read),
    (5, Access::ReadWrite),
];

/// The density pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "density.wgsl", SOURCE, "density", BINDINGS)
}
