//! The fluid module on the GPU: the force pass (with the WCSPH pressure terms or
//! without), the XSPH sum and kick, and the module uniform `fluid` (per material:
//! viscosity and XSPH; per material pair: the mixed viscosity and the mass ratio).

use crate::layout::MAX_MATERIALS;
use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{self, Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::modules::fluid::FluidConsts;
use floe_engine::modules::fluid::viscosity::ViscosityModel;

/// The bindings of the force pass with the WCSPH pressure terms (a kernel walking
/// the same neighbours for another pass as well binds these first).
pub const FORCES_WITH_PRESSURE_BINDINGS: [(Access, &str); 10] = [
    (U, "params"),
    (U, "fluid"),
    (R, "x"),
    (R, "v"),
    (R, "rho"),
    (R, "starts"),
    (R, "walls"),
    (W, "a"),
    (R, "pterm"),
    (R, "wall_p"),
];

/// Gravity, viscosity and the WCSPH pressure force.
pub static FORCES_WITH_PRESSURE: GpuPass = GpuPass {
    name: "fluid.forces",
    source: walk_kernel!("forces.wgsl", "forces_pressure.wgsl", "forces_walk.wgsl"),
    entry: "main",
    bindings: &FORCES_WITH_PRESSURE_BINDINGS,
    space: PARTICLES,
    when: has_pressure_terms,
};

/// Whether the scheme gives the force pass pressure terms (WCSPH's `p / rho^2`).
pub fn has_pressure_terms(model: &Model) -> bool {
    model.layout.spec("pterm").is_some()
}

/// Gravity and viscosity (schemes that solve pressure on their own).
pub static FORCES: GpuPass = GpuPass {
    name: "fluid.forces",
    source: walk_kernel!("forces.wgsl", "forces_plain.wgsl", "forces_walk.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "fluid"), (R, "x"), (R, "v"), (R, "rho"), (R, "starts"), (R, "walls"), (W, "a")],
    space: PARTICLES,
    when: |m| !has_pressure_terms(m),
};

/// The XSPH sum.
pub static XSPH: GpuPass = GpuPass {
    name: "fluid.xsph",
    source: walk_kernel!(fluid_only; "xsph.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "fluid"), (R, "x"), (R, "v"), (R, "rho"), (R, "starts"), (W, "xsph")],
    space: PARTICLES,
    when: always,
};

/// The XSPH kick.
pub static XSPH_KICK: GpuPass = GpuPass {
    name: "fluid.xsph_kick",
    source: particle_kernel!("xsph_kick.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "xsph"), (W, "v")],
    space: PARTICLES,
    when: always,
};

/// The `fluid` uniform (`Fluid` in forces.wgsl and xsph.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct FluidParams {
    material: [[f32; 4]; MAX_MATERIALS],
    pair: [[f32; 4]; MAX_MATERIALS * MAX_MATERIALS],
}

/// (kind, a, b) of a viscosity model.
fn viscosity(v: &ViscosityModel) -> [f32; 3] {
    match *v {
        ViscosityModel::None => [0.0, 0.0, 0.0],
        ViscosityModel::Laplacian { mu } => [1.0, mu, 0.0],
        ViscosityModel::Artificial { alpha_c_h, eps_h2 } => [2.0, alpha_c_h, eps_h2],
    }
}

/// The uniform's bytes, when the scene has the fluid module.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if !model.has_module("fluid") {
        return None;
    }
    let c: &FluidConsts = model.consts();
    let n = model.materials.len();
    let mut p = FluidParams::zeroed();
    for a in 0..n {
        let [kind, x, y] = viscosity(&c.viscosity[a]);
        p.material[a] = [kind, x, y, c.xsph[a]];
        for b in 0..n {
            let [kind, x, y] = viscosity(&c.pair_viscosity[a * n + b]);
            p.pair[a * MAX_MATERIALS + b] = [kind, x, y, c.mass_ratio[a * n + b]];
        }
    }
    Some(bytemuck::bytes_of(&p).to_vec())
}
