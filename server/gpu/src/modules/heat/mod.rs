//! The heat module on the GPU: conduction, Boussinesq buoyancy and the
//! temperature integration, with the module uniform `heat` (per material:
//! conductivity, heat capacity, expansion; per pair: the combined conductivity;
//! the walls held at a temperature and the heat sources; per material: the
//! viscosity's temperature law; per material that melts or freezes: its phase
//! change).

use crate::layout::MAX_MATERIALS;
use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::modules::heat::viscosity::MAX_POINTS;
use floe_engine::modules::heat::{HeatConsts, MAX_BOXES};

/// dT/dt from conduction, walls and sources.
pub static CONDUCTION: GpuPass = GpuPass {
    name: "heat.conduction",
    source: walk_kernel!(walls_if; "heat.wgsl", "conduction.wgsl", "conduction_walk.wgsl", "conduction_plain.wgsl"),
    entry: "main",
    bindings: &CONDUCTION_BINDINGS,
    space: PARTICLES,
    when: |m| !has_input(m),
};

/// The conduction's bindings.
const CONDUCTION_BINDINGS: [(crate::program::Access, &str); 8] = [
    (U, "params"),
    (U, "heat"),
    (R, "x"),
    (R, "rho"),
    (R, "temperature"),
    (R, "starts"),
    (R, "walls"),
    (W, "heat_rate"),
];

/// The same, writing also the part of dT/dt from walls and sources, where a
/// fluid melts and heat enters from outside.
pub static CONDUCTION_INPUT: GpuPass = GpuPass {
    name: "heat.conduction",
    source: walk_kernel!(walls_if; "heat.wgsl", "conduction.wgsl", "conduction_walk.wgsl", "conduction_input.wgsl"),
    entry: "main",
    bindings: &crate::program::join::<8, 1, 9>(CONDUCTION_BINDINGS, [(W, "heat_input")]),
    space: PARTICLES,
    when: has_input,
};

/// Whether the scene sums the heat walls and sources give (`heat_input`).
pub fn has_input(model: &Model) -> bool {
    model.layout.spec("heat_input").is_some()
}

/// The heat taken in from walls and sources, summed.
pub static INPUT: GpuPass = GpuPass {
    name: "heat.input",
    source: particle_kernel!("heat.wgsl", "compensated.wgsl", "input.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "dt"),
        (U, "heat"),
        (R, "x"),
        (R, "heat_input"),
        (W, "heat_in"),
        (W, "heat_in_carry"),
    ],
    space: PARTICLES,
    when: always,
};

/// The Boussinesq term of the body force.
pub static BUOYANCY: GpuPass = GpuPass {
    name: "heat.buoyancy",
    source: particle_kernel!("heat.wgsl", "buoyancy.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "heat"), (R, "x"), (R, "temperature"), (W, "a")],
    space: PARTICLES,
    when: always,
};

/// `T += dt dT/dt`, compensated.
pub static INTEGRATE: GpuPass = GpuPass {
    name: "heat.integrate",
    source: particle_kernel!("compensated.wgsl", "integrate.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (W, "temperature"), (W, "temperature_carry"), (R, "heat_rate")],
    space: PARTICLES,
    when: always,
};

/// The integration where a fluid melts: temperature, or enthalpy, liquid fraction
/// and phase.
pub static MELT: GpuPass = GpuPass {
    name: "heat.melt",
    source: particle_kernel!("heat.wgsl", "compensated.wgsl", "melt.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "dt"),
        (U, "heat"),
        (W, "x"),
        (W, "temperature"),
        (W, "temperature_carry"),
        (R, "heat_rate"),
        (W, "enthalpy"),
        (W, "enthalpy_carry"),
        (W, "liquid_fraction"),
    ],
    space: PARTICLES,
    when: always,
};

/// The particles' viscosity from their temperature.
pub static VISCOSITY: GpuPass = GpuPass {
    name: "heat.viscosity",
    source: particle_kernel!("heat.wgsl", "viscosity.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "heat"), (R, "x"), (R, "temperature"), (W, "mu")],
    space: PARTICLES,
    when: always,
};

/// The shift factor of the snow module's rheology from the temperature.
pub static VISCOSITY_SHIFT: GpuPass = GpuPass {
    name: "heat.viscosity_shift",
    source: particle_kernel!("heat.wgsl", "viscosity.wgsl"),
    entry: "shift",
    bindings: &[(U, "params"), (U, "heat"), (R, "x"), (R, "temperature"), (W, "viscosity_shift")],
    space: PARTICLES,
    when: always,
};

/// The `heat` uniform (`Heat` in heat.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct HeatParams {
    material: [[f32; 4]; MAX_MATERIALS],
    pair: [[f32; 4]; MAX_MATERIALS * MAX_MATERIALS],
    reference: f32,
    eps_h2: f32,
    n_walls: u32,
    n_sources: u32,
    wall_min: [[f32; 4]; MAX_BOXES],
    wall_max: [[f32; 4]; MAX_BOXES],
    source_min: [[f32; 4]; MAX_BOXES],
    source_max: [[f32; 4]; MAX_BOXES],
    gravity: [f32; 4],
    law: [[f32; 4]; MAX_MATERIALS],
    law_clamp: [[f32; 4]; MAX_MATERIALS],
    table: [[f32; 4]; MAX_MATERIALS * MAX_POINTS / 2],
    phase: [[f32; 4]; MAX_MATERIALS],
    phase_of: [[u32; 4]; MAX_MATERIALS],
}

/// The uniform's bytes, when the scene has the heat module.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if !model.has_module("heat") {
        return None;
    }
    let c: &HeatConsts = model.consts();
    let n = model.materials.len();
    let h = 0.5 * model.kernel.support();
    let mut p = HeatParams::zeroed();
    for a in 0..n {
        p.material[a] = [c.conductivity[a], c.capacity[a], c.expansion[a], 0.0];
        let law = &c.viscosity[a];
        p.law[a] = [f32::from_bits(law.kind as u32), law.p[0], law.p[1], law.p[2]];
        p.law_clamp[a] = [law.max, f32::from_bits(law.points as u32), law.inv_reference, 0.0];
        for (k, pair) in law.table.chunks(2).enumerate() {
            p.table[a * MAX_POINTS / 2 + k] = [pair[0][0], pair[0][1], pair[1][0], pair[1][1]];
        }
        for b in 0..n {
            p.pair[a * MAX_MATERIALS + b][0] = c.pair_conductivity[a * n + b];
        }
        if let Some(ph) = c.phases[a] {
            p.phase[a] = [ph.melting_point, ph.latent, ph.solid_capacity, ph.liquid_capacity];
            p.phase_of[a] = [ph.solid, ph.liquid, 1, 0];
        }
    }
    (p.reference, p.eps_h2) = (c.reference, 0.01 * h * h);
    p.gravity = c.gravity.extend(0.0).into();
    (p.n_walls, p.n_sources) = (c.walls.len() as u32, c.sources.len() as u32);
    for (k, (b, t)) in c.walls.iter().enumerate() {
        p.wall_min[k] = [b.min.x, b.min.y, b.min.z, *t];
        p.wall_max[k] = [b.max.x, b.max.y, b.max.z, 0.0];
    }
    for (k, s) in c.sources.iter().enumerate() {
        let (lo, hi) = (s.region.min, s.region.max);
        p.source_min[k] = [lo.x, lo.y, lo.z, s.power];
        p.source_max[k] = [hi.x, hi.y, hi.z, s.layer];
    }
    Some(bytemuck::bytes_of(&p).to_vec())
}
