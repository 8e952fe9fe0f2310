//! The GPU passes: one WGSL file per kernel (`common.wgsl` prepended to the
//! particle kernels) and one Rust file owning its pipelines and bindings.
//! [`Programs`] compiles them once per device; every scene on that device
//! shares them.

pub mod density;
pub mod forces;
pub mod grid;
pub mod integrate;
pub mod measure;
pub mod quantize;
pub mod reorder;
pub mod scan;
pub mod wall_pressure;

use crate::program::Kernel;
use wgpu::Device;

/// Joins `common.wgsl` with a particle kernel's own source.
macro_rules! particle_kernel {
    ($file:literal) => {
        concat!(include_str!("common.wgsl"), "\n", include_str!($file))
    };
}
pub(crate) use particle_kernel;

/// Every shader's label and complete WGSL source (for validation and docs).
pub const SOURCES: &[(&str, &str)] = &[
    ("grid", grid::SOURCE),
    ("scan", scan::SOURCE),
    ("reorder", reorder::SOURCE),
    ("density", density::SOURCE),
    ("wall_pressure", wall_pressure::SOURCE),
    ("forces", forces::SOURCE),
    ("measure", measure::SOURCE),
    ("integrate", integrate::SOURCE),
    ("quantize", quantize::SOURCE),
];

/// All compiled kernels of one device.
#[derive(Debug)]
pub struct Programs {
    pub grid: grid::Grid,
    pub scan: scan::Scan,
    pub reorder: reorder::Reorder,
    pub density: Kernel,
    pub wall_pressure: Kernel,
    pub forces: Kernel,
    pub measure: measure::Measure,
    pub integrate: integrate::Integrate,
    pub quantize: Kernel,
}

impl Programs {
    /// Compiles every kernel for `device`.
    pub fn new(device: &Device) -> Self {
        Self {
            grid: grid::Grid::new(device),
            scan: scan::Scan::new(device),
            reorder: reorder::Reorder::new(device),
            density: density::kernel(device),
            wall_pressure: wall_pressure::kernel(device),
            forces: forces::kernel(device),
            measure: measure::Measure::new(device),
            integrate: integrate::Integrate::new(device),
            quantize: quantize::kernel(device),
        }
    }
}
