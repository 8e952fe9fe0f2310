//! The GPU halves of the engine's schemes, in folders named as the engine's.

pub mod dfsph;
pub mod wcsph;

use crate::pass::{GpuPass, UniformSource};

/// Every scheme's GPU passes.
pub static PASSES: &[&GpuPass] = &[
    &wcsph::EOS,
    &wcsph::WALL_PRESSURE,
    &wcsph::TRANSPORT,
    &wcsph::CONTINUITY,
    &wcsph::INTEGRATE_DENSITY,
    &dfsph::FACTOR,
    &dfsph::DIVERGENCE_WARM,
    &dfsph::DIVERGENCE_KICK,
    &dfsph::DIVERGENCE_ERROR,
    &dfsph::DENSITY_WARM,
    &dfsph::DENSITY_KICK,
    &dfsph::DENSITY_ERROR,
    &dfsph::cg::HELD,
    &dfsph::cg::CLOSED,
    &dfsph::cg::SHIFT,
    &dfsph::cg::SHIFT_APPLY,
    &dfsph::cg::DIVERGENCE_WARM,
    &dfsph::cg::DIVERGENCE_START,
    &dfsph::cg::DIVERGENCE_ADJUST,
    &dfsph::cg::DIVERGENCE_RESIDUAL,
    &dfsph::cg::DIVERGENCE_UPDATE,
    &dfsph::cg::DIVERGENCE_CLAMP,
    &dfsph::cg::WALL_PRESSURE,
    &dfsph::cg::DENSITY_WARM,
    &dfsph::cg::DENSITY_START,
    &dfsph::cg::DENSITY_ADJUST,
    &dfsph::cg::DENSITY_RESIDUAL,
    &dfsph::cg::DENSITY_UPDATE,
    &dfsph::cg::DENSITY_CLAMP,
    &dfsph::cg::GRADIENT,
    &dfsph::cg::PRODUCT,
    &dfsph::cg::DIRECTION,
];

/// Every scheme's uniform.
pub static UNIFORMS: &[(&str, UniformSource)] =
    &[("wcsph", wcsph::uniform), ("dfsph", dfsph::uniform), ("dfsph.cg", dfsph::cg::uniform)];
