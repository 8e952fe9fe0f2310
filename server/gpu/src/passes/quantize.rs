//! Frame positions quantised on the GPU (see quantize.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel};
use wgpu::Device;

/// Source of quantize.wgsl.
pub const SOURCE: &str = super::particle_kernel!("quantize.wgsl");

/// params, grid, positions, slot of each id, packed codes.
const BINDINGS: &[(u32, Access)] = &[(0, U), (1, U), (2, R), (3, R), (4, W)];

/// The frame position quantiser.
pub fn kernel(device: &Device) -> Kernel {
    Kernel::main(device, "quantize.wgsl", SOURCE, "quantize", BINDINGS)
}
