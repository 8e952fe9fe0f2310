//! Wall particle pressures extrapolated from the fluid (see wall_pressure.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of wall_pressure.wgsl.
pub const SOURCE: &str = super::particle_kernel!("wall_pressure.wgsl");

/// params, positions, cell starts, walls, (rho, p/rho^2), wall pressures.
const BINDINGS: &[(u32, Access)] = &[(0, U), (1, R), (2, R), (3, R), (4, R), (5, W)];

/// The wall pressure pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "wall_pressure.wgsl", SOURCE, "wall pressure", BINDINGS)
}
