//! The core's per-particle viscosity on the GPU (floe-engine `viscosity`): its
//! force with the uniform `viscosity` (the walls' shear factor and the pair sum's
//! lattice normalisation), and [`implicit`]: that force's implicit solve.

pub mod implicit;

use crate::pass::{GpuPass, UniformSource, always};
use crate::passes::walk_kernel;
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::viscosity::VaryingViscosity;

/// The viscous force of the per-particle viscosities (explicit solver).
pub static FORCE: GpuPass = GpuPass {
    name: "viscosity.force",
    source: walk_kernel!("varying_walls.wgsl", "varying.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "viscosity"),
        (R, "x"),
        (R, "v"),
        (R, "rho"),
        (R, "mu"),
        (R, "starts"),
        (R, "walls"),
        (W, "a"),
    ],
    space: PARTICLES,
    when: always,
};

/// The viscosity's passes.
pub static PASSES: &[&GpuPass] = &[
    &FORCE,
    &implicit::DIAGONAL,
    &implicit::PRECONDITION,
    &implicit::PRODUCT,
    &implicit::UPDATE,
    &implicit::DIRECTION,
];

/// The `viscosity` uniform, when the scene's viscosity varies per particle.
pub const UNIFORM: (&str, UniformSource) = ("viscosity", uniform);

fn uniform(model: &Model) -> Option<Vec<u8>> {
    model.layout.spec("mu")?;
    let c = model.consts::<VaryingViscosity>();
    Some(bytemuck::bytes_of(&[c.wall_shear, c.scale, 0.0, 0.0]).to_vec())
}
