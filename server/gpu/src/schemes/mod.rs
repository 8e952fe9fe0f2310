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
];

/// Every scheme's uniform.
pub static UNIFORMS: &[(&str, UniformSource)] = &[("wcsph", wcsph::uniform), ("dfsph", dfsph::uniform)];
