//! Frame positions quantised on the GPU (see quantize.wgsl).

use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of quantize.wgsl.
pub const SOURCE: &str = super::particle_kernel!("quantize.wgsl");

/// params, grid, positions, slot of each id, packed codes.
const BINDINGS: &[(u32, Access)] =
    &[(0, Access::Uniform), (1, Access::Uniform), (2, Access::Read), (3, Access::Read), (4, Access::ReadWrite)];

/// The frame position quantiser.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "quantize.wgsl", SOURCE, "quantize", BINDINGS)
}
