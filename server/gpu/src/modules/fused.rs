//! Kernels doing passes of several modules in one neighbour walk. A fusion knows
//! the modules it joins, so it lives here beside the lists (`modules/mod.rs`),
//! not in either module's folder.

use crate::modules::fluid::{FORCES_WITH_PRESSURE_BINDINGS, has_pressure_terms};
use crate::pass::{Fused, GpuPass};
use crate::passes::walk_kernel;
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;

/// The fluid's force pass (with WCSPH's pressure terms) and conduction in one
/// neighbour walk: conduction then costs little more than its arithmetic. Ten
/// storage buffers: where a device allows fewer, the two passes run their own
/// kernels, as they do where conduction also writes `heat_input`.
pub static FORCES_AND_CONDUCTION: Fused = Fused {
    passes: &["fluid.forces", "heat.conduction"],
    kernel: GpuPass {
        name: "fluid.forces+heat.conduction",
        source: walk_kernel!(
            "fluid/forces.wgsl",
            "fluid/forces_pressure.wgsl",
            "heat/heat.wgsl",
            "heat/conduction.wgsl",
            "forces_conduction.wgsl"
        ),
        entry: "main",
        bindings: &crate::program::join::<10, 3, 13>(
            FORCES_WITH_PRESSURE_BINDINGS,
            [(U, "heat"), (R, "temperature"), (W, "heat_rate")],
        ),
        space: PARTICLES,
        when: |m| has_pressure_terms(m) && !crate::modules::heat::has_input(m),
    },
};
