//! Counting sort by cell: `count`, `scatter` and `settle` (see grid.wgsl).

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Access, Kernel, Layout, module};
use wgpu::Device;

/// Source of grid.wgsl.
pub const SOURCE: &str = super::particle_kernel!("grid.wgsl");

const BINDINGS: &[(u32, Access)] = &[(0, U), (1, R), (2, W), (3, W), (4, W)];

/// The three sort kernels; they share one binding layout:
/// params, positions, (cell, rank) per particle, per-cell counts then starts, order.
#[derive(Debug)]
pub struct Grid {
    pub count: Kernel,
    pub scatter: Kernel,
    pub settle: Kernel,
}

impl Grid {
    pub fn new(device: &Device) -> Self {
        let m = module(device, "grid.wgsl", SOURCE);
        let layout = Layout::new(device, "grid", BINDINGS);
        Self {
            count: Kernel::new(device, &m, "grid count", "count", &layout, 128),
            scatter: Kernel::new(device, &m, "grid scatter", "scatter", &layout, 128),
            settle: Kernel::new(device, &m, "grid settle", "settle", &layout, 128),
        }
    }
}
