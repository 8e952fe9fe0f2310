//! The GPU halves of the engine's modules, in folders named as the engine's.

pub mod fluid;
pub mod fused;
pub mod heat;
pub mod snow;
pub mod snowfall;
pub mod solid;

use crate::pass::{Fused, GpuPass, UniformSource};

/// Every module's GPU passes.
pub static PASSES: &[&GpuPass] = &[
    &fluid::FORCES_WITH_PRESSURE,
    &fluid::FORCES,
    &fluid::XSPH,
    &fluid::XSPH_KICK,
    &heat::CONDUCTION,
    &heat::CONDUCTION_INPUT,
    &heat::BUOYANCY,
    &heat::INTEGRATE,
    &heat::MELT,
    &heat::INPUT,
    &heat::VISCOSITY,
    &heat::VISCOSITY_SHIFT,
    &snow::SHEAR,
    &snow::SHEAR_SHIFTED,
    &snowfall::EMIT,
    &snowfall::FALL,
    &snowfall::SURFACE,
    &solid::LEAVE,
    &solid::REJOIN,
    &solid::LIVE,
    &solid::GATHER,
    &solid::CENTRE_SUM,
    &solid::MOMENT,
    &solid::MOMENT_SUM,
    &solid::ROTATE,
    &solid::WAY,
    &solid::DEFORMATION_SUM,
    &solid::WEIGH,
    &solid::WAY_SUM,
    &solid::WEIGHT_SUM,
    &solid::PROJECT,
    &solid::STIFFEN,
    &solid::PROJECT_BLENDED,
    &solid::ORIENT_PREDICT,
    &solid::ELLIPSOID,
    &solid::ORIENT_TURN,
    &solid::ORIENT_SUM,
    &solid::ORIENT_UPDATE,
    &solid::MOTION,
    &solid::VELOCITY_SUM,
    &solid::SPIN,
    &solid::SPIN_SUM,
    &solid::INERTIA_SUM,
    &solid::RIGID,
    &solid::RIGID_WAY,
    &solid::DAMP,
    &solid::DAMP_BLENDED,
];

/// Kernels doing several modules' passes in one neighbour walk.
pub static FUSED: &[&Fused] = &[&fused::FORCES_AND_CONDUCTION];

/// Every module's uniform.
pub static UNIFORMS: &[(&str, UniformSource)] = &[
    ("fluid", fluid::uniform),
    ("heat", heat::uniform),
    ("snow", snow::uniform),
    ("snowfall", snowfall::uniform),
    ("solid", solid::uniform),
];
