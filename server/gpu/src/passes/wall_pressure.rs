//! Wall particle pressures extrapolated from the fluid (see wall_pressure.wgsl).

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

/// Source of wall_pressure.wgsl.
pub const SOURCE: &str = super::particle_kernel!("wall_pressure.wgsl");

/// params, positions, cell starts, walls, (rho, p/rho^2), wall pressures.
#[derive(Debug)]
pub struct WallPressure {
    pub kernel: Kernel,
}

impl WallPressure {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "wall_pressure.wgsl", SOURCE);
        Self {
            kernel: Kernel::new(
                device,
                &m,
                "wall pressure",
                "main",
                &Layout::new(device, "wall pressure", BINDINGS),
                128,
            ),
        }
    }
}
