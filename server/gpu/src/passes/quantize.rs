//! Frame positions quantised on the GPU (see quantize.wgsl).

use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of quantize.wgsl.
pub const SOURCE: &str = super::particle_kernel!("quantize.wgsl");

const BINDINGS: &[(u32, Access)] =
    &[(0, Access::Uniform), (1, Access::Uniform), (2, Access::Read), (3, Access::Read), (4, Access::ReadWrite)];

/// params, grid, positions, slot of each id, packed codes.
#[derive(Debug)]
pub struct Quantize {
    pub kernel: Kernel,
}

impl Quantize {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "quantize.wgsl", SOURCE);
        Self { kernel: Kernel::new(device, &m, "quantize", "main", &Layout::new(device, "quantize", BINDINGS), 128) }
    }
}
