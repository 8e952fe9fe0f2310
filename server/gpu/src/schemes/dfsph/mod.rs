//! The DFSPH scheme on the GPU: the factor, each solve's warm start, kick and
//! error (the conjugate-gradient solves' passes: [`cg`]), and the uniform `dfsph`
//! (the warm start fraction, the neighbourhood a particle needs in the
//! divergence-free solve and the walls' factor). The kicks and errors read the
//! step's dt from the core's `dt` uniform, which the backend writes before a pass
//! that binds it runs with a new dt.

use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{self, Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::schemes::dfsph::cg::SURFACE_DENSITY;
use floe_engine::schemes::dfsph::{DfsphConsts, FULL_NEIGHBOURHOOD, WARM_START};

pub mod cg;

/// `alpha` from the step's neighbours.
pub static FACTOR: GpuPass = GpuPass {
    name: "dfsph.factor",
    source: walk_kernel!("factor.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dfsph"), (R, "x"), (R, "starts"), (R, "walls"), (W, "alpha")],
    space: PARTICLES,
    when: always,
};

const fn warm(name: &'static str, bindings: &'static [(Access, &'static str)]) -> GpuPass {
    GpuPass { name, source: particle_kernel!("warm.wgsl"), entry: "main", bindings, space: PARTICLES, when: always }
}

const fn kick(name: &'static str, bindings: &'static [(Access, &'static str)]) -> GpuPass {
    GpuPass {
        name,
        source: walk_kernel!("gradient_sum.wgsl", "kick.wgsl"),
        entry: "main",
        bindings,
        space: PARTICLES,
        when: always,
    }
}

const fn error(name: &'static str, entry: &'static str, bindings: &'static [(Access, &'static str)]) -> GpuPass {
    GpuPass {
        name,
        source: particle_kernel!("rate.wgsl", "error.wgsl"),
        entry,
        bindings,
        space: PARTICLES,
        when: always,
    }
}

/// The divergence-free solve's warm start.
pub static DIVERGENCE_WARM: GpuPass =
    warm("dfsph.divergence_warm", &[(U, "params"), (U, "dfsph"), (W, "kappa_v"), (W, "dkappa_v")]);
/// The divergence-free solve's kick.
pub static DIVERGENCE_KICK: GpuPass = kick(
    "dfsph.divergence_kick",
    &[
        (U, "params"),
        (U, "dt"),
        (U, "dfsph"),
        (R, "x"),
        (R, "starts"),
        (R, "walls"),
        (R, "dkappa_v"),
        (W, "v"),
        (W, "kappa_v"),
    ],
);
/// The divergence-free solve's error.
pub static DIVERGENCE_ERROR: GpuPass = error(
    "dfsph.divergence_error",
    "divergence",
    &[
        (U, "params"),
        (U, "dt"),
        (U, "dfsph"),
        (R, "x"),
        (R, "v"),
        (R, "rho"),
        (R, "alpha"),
        (R, "starts"),
        (R, "walls"),
        (W, "dkappa_v"),
        (W, "divergence_error"),
    ],
);
/// The constant-density solve's warm start.
pub static DENSITY_WARM: GpuPass =
    warm("dfsph.density_warm", &[(U, "params"), (U, "dfsph"), (W, "kappa"), (W, "dkappa")]);
/// The constant-density solve's kick.
pub static DENSITY_KICK: GpuPass = kick(
    "dfsph.density_kick",
    &[
        (U, "params"),
        (U, "dt"),
        (U, "dfsph"),
        (R, "x"),
        (R, "starts"),
        (R, "walls"),
        (R, "dkappa"),
        (W, "v"),
        (W, "kappa"),
    ],
);
/// The constant-density solve's error.
pub static DENSITY_ERROR: GpuPass = error(
    "dfsph.density_error",
    "density",
    &[
        (U, "params"),
        (U, "dt"),
        (U, "dfsph"),
        (R, "x"),
        (R, "v"),
        (R, "rho"),
        (R, "alpha"),
        (R, "starts"),
        (R, "walls"),
        (W, "dkappa"),
        (W, "density_error"),
    ],
);

/// The uniform's bytes (`dfsph`: the warm start fraction, the neighbours a particle
/// needs, the walls' factor, the density below which the CG holds a particle), when
/// the scene is stepped by DFSPH.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    (model.scheme.id == "dfsph").then(|| {
        let c = model.consts::<DfsphConsts>().wall_factor;
        bytemuck::bytes_of(&[WARM_START, FULL_NEIGHBOURHOOD as f32, c, SURFACE_DENSITY]).to_vec()
    })
}
