//! The GPU halves of the engine's schemes, in folders named as the engine's.

pub mod wcsph;

use crate::pass::{GpuPass, UniformSource};

/// Every scheme's GPU passes.
pub static PASSES: &[&GpuPass] = &[&wcsph::EOS, &wcsph::WALL_PRESSURE];

/// Every scheme's uniform.
pub static UNIFORMS: &[(&str, UniformSource)] = &[("wcsph", wcsph::uniform)];
