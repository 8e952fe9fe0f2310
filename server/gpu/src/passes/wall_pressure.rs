//! Wall particle pressures extrapolated from the fluid (see wall_pressure.wgsl).

use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of wall_pressure.wgsl.
pub const SOURCE: &str = super::particle_kernel!("wall_pressure.wgsl");

/// params, positions, cell starts, walls, (rho, p/rho^2), wall pressures.
const BINDINGS: &[(u32, Access)] = &[
    (0, Access::Uniform),
    (1, Access::Read),
    (2, Access::Read),
    (3, Access::Read),
    (4, Access::Read),
    (5, Access::ReadWrite),
];

/// The wall pressure pass.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "wall_pressure.wgsl", SOURCE, "wall pressure", BINDINGS)
}
