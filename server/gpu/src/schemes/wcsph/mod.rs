//! The WCSPH scheme on the GPU: the equation of state, the walls' pressure, the
//! transport velocity's push, δ-SPH's density rate and its integration, and the
//! uniform `wcsph` (wcsph.wgsl: per material the equation of state, the
//! transport's background pressure, δ-SPH's constants).

use crate::layout::MAX_MATERIALS;
use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::attrs::{PARTICLES, WALLS};
use floe_engine::model::Model;
use floe_engine::schemes::wcsph::WcsphConsts;
use floe_engine::schemes::wcsph::eos::Law;

/// `p / rho^2` from density.
pub static EOS: GpuPass = GpuPass {
    name: "wcsph.eos",
    source: particle_kernel!("wcsph.wgsl", "eos.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "wcsph"), (R, "x"), (R, "rho"), (W, "pterm")],
    space: PARTICLES,
    when: always,
};

/// The walls' pressure.
pub static WALL_PRESSURE: GpuPass = GpuPass {
    name: "wcsph.wall_pressure",
    source: particle_kernel!("wall_pressure.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "x"), (R, "starts"), (R, "walls"), (R, "rho"), (R, "pterm"), (W, "wall_p")],
    space: WALLS,
    when: always,
};

/// The transport velocity's push (scenes with `solver.transport_velocity`).
pub static TRANSPORT: GpuPass = GpuPass {
    name: "wcsph.transport",
    source: walk_kernel!("wcsph.wgsl", "transport.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "wcsph"), (R, "x"), (R, "starts"), (R, "walls"), (R, "rho"), (W, "a_transport")],
    space: PARTICLES,
    when: always,
};

/// δ-SPH's density rate (scenes with `solver.delta_sph`).
pub static CONTINUITY: GpuPass = GpuPass {
    name: "wcsph.continuity",
    source: walk_kernel!("wcsph.wgsl", "continuity.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "wcsph"), (R, "x"), (R, "v"), (R, "rho"), (R, "starts"), (R, "walls"), (W, "drho")],
    space: PARTICLES,
    when: always,
};

/// δ-SPH's `rho += dt drho`.
pub static INTEGRATE_DENSITY: GpuPass = GpuPass {
    name: "wcsph.integrate_density",
    source: particle_kernel!("integrate_density.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (R, "drho"), (W, "rho")],
    space: PARTICLES,
    when: always,
};

/// The `wcsph` uniform (`Wcsph` in wcsph.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct WcsphParams {
    eos: [[f32; 4]; MAX_MATERIALS],
    /// Background pressure per material, four to a vector.
    background: [[f32; 4]; MAX_MATERIALS / 4],
    /// The transport velocity's background pressure (Pa) in x, 0 without one.
    transport: [f32; 4],
    /// δ-SPH's eta^2 (m^2), 0 without it.
    delta: [f32; 4],
    /// δ-SPH's `rho0 g / c^2` (kg/m^4) and diffusion coefficient (m^2/s) per material.
    delta_material: [[f32; 4]; MAX_MATERIALS],
}

/// The uniform's bytes, when the scene is stepped by WCSPH.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if model.scheme.id != "wcsph" {
        return None;
    }
    let c: &WcsphConsts = model.consts();
    let mut p = WcsphParams::zeroed();
    for (m, e) in c.eos.iter().enumerate() {
        p.eos[m] = match e.law {
            Law::Tait { rho0, b, gamma } => [0.0, b, gamma, rho0],
            Law::Linear { rho0, k } => [1.0, k, 1.0, rho0],
        };
        p.background[m / 4][m % 4] = e.background;
    }
    p.transport[0] = c.transport.unwrap_or(0.0);
    if let Some(d) = &c.delta {
        p.delta = [d.eta2, 0.0, 0.0, 0.0];
        for (m, (h, k)) in d.hydrostatic.iter().zip(&d.coefficient).enumerate() {
            p.delta_material[m] = [h.x, h.y, h.z, *k];
        }
    }
    Some(bytemuck::bytes_of(&p).to_vec())
}
