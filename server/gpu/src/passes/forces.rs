//! Accelerations and XSPH corrections (see forces.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of forces.wgsl.
pub const SOURCE: &str = super::particle_kernel!("forces.wgsl");

/// params, positions, velocities, (rho, p/rho^2), cell starts, walls, wall cell
/// starts, wall pressures, accelerations then XSPH corrections.
const BINDINGS: &[(u32, Access)] = &[(0, U), (1, R), (2, R), (3, R), (4, R), (5, R), (6, R), (7, R), (8, W)];

/// The force pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "forces.wgsl", SOURCE, "forces", BINDINGS)
}
