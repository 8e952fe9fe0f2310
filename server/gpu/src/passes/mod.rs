//! The core's GPU kernels: one WGSL file per kernel (`common.wgsl` prepended to the
//! particle kernels), compiled once per device into [`Programs`] that every scene
//! on it shares. Plan passes ([`crate::pass`]: this core's density, the schemes'
//! and the modules') are compiled on first use.

pub mod scan;

use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use crate::program::{Kernel, Layout, module};
use wgpu::Device;

/// Joins `common.wgsl` with a particle kernel's own source(s).
macro_rules! particle_kernel {
    ($($file:literal),+) => {
        concat!(include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/passes/common.wgsl")), $("\n", include_str!($file)),+)
    };
}
pub(crate) use particle_kernel;

/// Joins `common.wgsl` and the neighbour walk `walk.wgsl` with a pair pass's terms
/// and hooks. The walk visits the wall neighbours too (`walk_walls.wgsl`), always,
/// or, after `walls_if;`, where the kernel's `walk_walls()` says so; after
/// `fluid_only;` it visits none (`walk_fluid.wgsl`); after `walls_only;` it visits
/// the wall neighbours alone (`walk_walls_only.wgsl`).
macro_rules! walk_kernel {
    (fluid_only; $($file:literal),+) => {
        walk_kernel!(@join "walk.wgsl", ["walk_fluid.wgsl"]; $($file),+)
    };
    (walls_if; $($file:literal),+) => {
        walk_kernel!(@join "walk.wgsl", ["walk_walls.wgsl"]; $($file),+)
    };
    (walls_only; $($file:literal),+) => {
        walk_kernel!(@join "walk_walls_only.wgsl", ["walk_walls.wgsl", "walk_walls_always.wgsl"]; $($file),+)
    };
    (@join $main:literal, [$($walk:literal),+]; $($file:literal),+) => {
        concat!(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/passes/common.wgsl")),
            "\n",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/passes/", $main)),
            $("\n", include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/passes/", $walk))),+,
            $("\n", include_str!($file)),+
        )
    };
    ($($file:literal),+) => {
        walk_kernel!(@join "walk.wgsl", ["walk_walls.wgsl", "walk_walls_always.wgsl"]; $($file),+)
    };
}
pub(crate) use walk_kernel;

/// Source of the counting sort (grid.wgsl).
pub const GRID: &str = particle_kernel!("grid.wgsl");
/// Source of the strided permutation (reorder.wgsl, stand-alone).
pub const REORDER: &str = include_str!("reorder.wgsl");
/// Source of the guard's reduction (measure.wgsl).
pub const MEASURE: &str = particle_kernel!("measure.wgsl");
/// Source of kick and drift (integrate.wgsl).
pub const INTEGRATE: &str = particle_kernel!("integrate.wgsl");
/// Source of the frame quantiser (quantize.wgsl).
pub const QUANTIZE: &str = particle_kernel!("quantize.wgsl");
/// Source of the generic reduction (reduce.wgsl, stand-alone).
pub const REDUCE: &str = include_str!("reduce.wgsl");
/// Source of summation density (density.wgsl), the core's plan pass.
pub const DENSITY: &str = particle_kernel!("density.wgsl");

/// Summation density, the core's plan pass `core.density`.
pub static DENSITY_PASS: crate::pass::GpuPass = crate::pass::GpuPass {
    name: "core.density",
    source: DENSITY,
    entry: "main",
    bindings: &[(U, "params"), (R, "x"), (R, "starts"), (R, "walls"), (W, "rho")],
    space: floe_engine::attrs::PARTICLES,
    when: crate::pass::always,
};

/// `x_predicted = x` (floe-engine `position_solve`).
pub static PREDICT_PASS: crate::pass::GpuPass = crate::pass::GpuPass {
    name: "core.predict",
    source: particle_kernel!("predict.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "x"), (W, "x_predicted")],
    space: floe_engine::attrs::PARTICLES,
    when: crate::pass::always,
};

/// `v += (x - x_predicted) / dt` (floe-engine `position_solve`).
pub static VELOCITY_FROM_POSITIONS_PASS: crate::pass::GpuPass = crate::pass::GpuPass {
    name: "core.velocity_from_positions",
    source: particle_kernel!("velocity_from_positions.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (R, "x"), (R, "x_predicted"), (W, "v")],
    space: floe_engine::attrs::PARTICLES,
    when: crate::pass::always,
};

/// `x_start = x`, `x += dt v` (floe-engine `position_solve::run_ahead`).
pub static LOOK_AHEAD_PASS: crate::pass::GpuPass = crate::pass::GpuPass {
    name: "core.look_ahead",
    source: particle_kernel!("look_ahead.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (R, "v"), (W, "x_start"), (W, "x")],
    space: floe_engine::attrs::PARTICLES,
    when: crate::pass::always,
};

/// `x = x_start` (floe-engine `position_solve::run_ahead`).
pub static LOOK_BACK_PASS: crate::pass::GpuPass = crate::pass::GpuPass {
    name: "core.look_back",
    source: particle_kernel!("look_back.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "x_start"), (W, "x")],
    space: floe_engine::attrs::PARTICLES,
    when: crate::pass::always,
};

/// Particles per partial of the reductions (their workgroup size).
pub const PER_PARTIAL: u32 = 256;

/// Every core shader's label and complete WGSL source (for validation and docs).
pub const SOURCES: &[(&str, &str)] = &[
    ("grid", GRID),
    ("scan", scan::SOURCE),
    ("reorder", REORDER),
    ("measure", MEASURE),
    ("integrate", INTEGRATE),
    ("quantize", QUANTIZE),
    ("reduce", REDUCE),
    ("density", DENSITY),
];

/// The core's compiled kernels on one device.
#[derive(Debug)]
pub struct Programs {
    /// params, positions, (cell, rank), counts then run starts, order.
    pub grid_count: Kernel,
    /// Same bindings.
    pub grid_scatter: Kernel,
    /// Same bindings.
    pub grid_settle: Kernel,
    /// The prefix sum.
    pub scan: scan::Scan,
    /// words, order, source, destination.
    pub permute: Kernel,
    /// words, (unused) order, ids, slot of each id.
    pub slots: Kernel,
    /// params, positions, velocities, accelerations, densities, partials.
    pub measure_partials: Kernel,
    /// Same bindings.
    pub measure_total: Kernel,
    /// params, step, positions, velocities, accelerations, constraints, terrain
    /// heights, transport accelerations.
    pub kick: Kernel,
    /// Same bindings.
    pub drift: Kernel,
    /// params, grid, positions, slot of each id, codes.
    pub quantize: Kernel,
    /// words, values, partials.
    pub reduce_partials: Kernel,
    /// Same bindings.
    pub reduce_total: Kernel,
}

impl Programs {
    /// Compiles every core kernel for `device`.
    pub fn new(device: &Device) -> Self {
        let grid = module(device, "grid.wgsl", GRID);
        let grid_layout = Layout::new(device, "grid", &[U, R, W, W, W]);
        let reorder = module(device, "reorder.wgsl", REORDER);
        let reorder_layout = Layout::new(device, "reorder", &[U, R, R, W]);
        let measure = module(device, "measure.wgsl", MEASURE);
        let measure_layout = Layout::new(device, "measure", &[U, R, R, R, R, W]);
        let integrate = module(device, "integrate.wgsl", INTEGRATE);
        let integrate_layout = Layout::new(device, "integrate", &[U, U, W, W, R, R, R, R]);
        let reduce = module(device, "reduce.wgsl", REDUCE);
        let reduce_layout = Layout::new(device, "reduce", &[U, R, W]);
        let k = |m: &wgpu::ShaderModule, label, entry, layout: &Layout, wg| {
            Kernel::new(device, m, label, entry, layout, wg)
        };
        Self {
            grid_count: k(&grid, "grid count", "count", &grid_layout, 128),
            grid_scatter: k(&grid, "grid scatter", "scatter", &grid_layout, 128),
            grid_settle: k(&grid, "grid settle", "settle", &grid_layout, 128),
            scan: scan::Scan::new(device),
            permute: k(&reorder, "reorder", "permute", &reorder_layout, 128),
            slots: k(&reorder, "slot of id", "slots", &reorder_layout, 128),
            measure_partials: k(&measure, "measure partials", "partials", &measure_layout, PER_PARTIAL),
            measure_total: k(&measure, "measure total", "total", &measure_layout, PER_PARTIAL),
            kick: k(&integrate, "kick", "kick", &integrate_layout, 128),
            drift: k(&integrate, "drift", "drift", &integrate_layout, 128),
            quantize: Kernel::single(device, "quantize", QUANTIZE, "main", &[U, U, R, R, W]),
            reduce_partials: k(&reduce, "reduce partials", "partials", &reduce_layout, PER_PARTIAL),
            reduce_total: k(&reduce, "reduce total", "total", &reduce_layout, PER_PARTIAL),
        }
    }
}
