//! Accelerations and XSPH corrections (see forces.wgsl).

use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of forces.wgsl.
pub const SOURCE: &str = super::particle_kernel!("forces.wgsl");

/// params, positions, velocities, (rho, p/rho^2), cell starts, walls, wall cell
/// starts, wall pressures, accelerations then XSPH corrections.
const BINDINGS: &[(u32, Access)] = &[
    (0, Access::Uniform),
    (1, Access::Read),
    (2, Access::Read),
    (3, Access::Read),
    (4, Access::Read),
    (5, Access::Read),
    (6, Access::Read),
    (7, Access::Read),
    (8, Access::ReadWrite),
];

/// The force pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "forces.wgsl", SOURCE, "forces", BINDINGS)
}
