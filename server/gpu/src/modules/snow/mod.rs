//! The snow module on the GPU: the shear-rate pass, with the module uniform `snow`
//! (per material: the viscosity law and its clamp). The force of the viscosities it
//! writes is the core's ([`crate::viscosity`]).

use crate::layout::MAX_MATERIALS;
use crate::pass::GpuPass;
use crate::passes::walk_kernel;
use crate::program::Access::{self, Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::modules::snow::SnowConsts;
use floe_engine::viscosity::VaryingViscosity;

/// Shear rate and viscosity per particle.
pub static SHEAR: GpuPass = GpuPass {
    name: "snow.shear",
    source: walk_kernel!("snow.wgsl", "shear.wgsl", "shear_plain.wgsl"),
    entry: "main",
    bindings: &SHEAR_BINDINGS,
    space: PARTICLES,
    when: |m| m.layout.spec("viscosity_shift").is_none(),
};

/// The same, each viscosity scaled by the heat module's temperature shift factor.
pub static SHEAR_SHIFTED: GpuPass = GpuPass {
    name: "snow.shear",
    source: walk_kernel!("snow.wgsl", "shear.wgsl", "shear_shifted.wgsl"),
    entry: "main",
    bindings: &crate::program::join::<9, 1, 10>(SHEAR_BINDINGS, [(R, "viscosity_shift")]),
    space: PARTICLES,
    when: |m| m.layout.spec("viscosity_shift").is_some(),
};

const SHEAR_BINDINGS: [(Access, &str); 9] = [
    (U, "params"),
    (U, "snow"),
    (R, "x"),
    (R, "v"),
    (R, "rho"),
    (R, "starts"),
    (R, "walls"),
    (W, "mu"),
    (W, "shear_rate"),
];

/// The `snow` uniform (`Snow` in snow.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct SnowParams {
    kind: [[f32; 4]; MAX_MATERIALS],
    p: [[f32; 4]; MAX_MATERIALS],
}

/// The uniform's bytes, when the scene has the snow module.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if !model.has_module("snow") {
        return None;
    }
    let c: &SnowConsts = model.consts();
    let wall_shear = model.consts::<VaryingViscosity>().wall_shear;
    let mut u = SnowParams::zeroed();
    for (m, law) in c.laws.iter().enumerate() {
        u.kind[m] = [f32::from_bits(law.kind as u32), law.max, wall_shear, 0.0];
        u.p[m] = law.p;
    }
    Some(bytemuck::bytes_of(&u).to_vec())
}
