//! DFSPH's conjugate-gradient solves on the GPU: the passes of floe-engine
//! `schemes::dfsph::cg`, one kernel each (both solves share a kernel, by entry point
//! or by bindings); the sums between them stay on the device (`dfsph_scalars`).

use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{self, Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;

const fn particles(
    name: &'static str,
    source: &'static str,
    entry: &'static str,
    bindings: &'static [(Access, &'static str)],
) -> GpuPass {
    GpuPass { name, source, entry, bindings, space: PARTICLES, when: always }
}

/// The held particles.
pub static HELD: GpuPass = particles(
    "dfsph.cg_held",
    particle_kernel!("rate.wgsl", "cg/held.wgsl"),
    "main",
    &[(U, "params"), (U, "dfsph"), (R, "x"), (R, "v"), (R, "rho"), (R, "starts"), (R, "walls"), (W, "dfsph_held")],
);

const WARM: &str = particle_kernel!("cg/warm.wgsl");
/// The divergence-free solve's warm start.
pub static DIVERGENCE_WARM: GpuPass = particles(
    "dfsph.cg_divergence_warm",
    WARM,
    "main",
    &[(U, "params"), (U, "dfsph"), (R, "dfsph_scalars"), (W, "kappa_v"), (W, "dkappa_v")],
);
/// The constant-density solve's warm start.
pub static DENSITY_WARM: GpuPass = particles(
    "dfsph.cg_density_warm",
    WARM,
    "main",
    &[(U, "params"), (U, "dfsph"), (R, "dfsph_scalars"), (W, "kappa"), (W, "dkappa")],
);

const START: &str = particle_kernel!("rate.wgsl", "cg/start.wgsl");
const START_BINDINGS: &[(Access, &str)] = &[
    (U, "params"),
    (U, "dt"),
    (U, "dfsph"),
    (R, "x"),
    (R, "v"),
    (R, "rho"),
    (R, "starts"),
    (R, "walls"),
    (R, "dfsph_held"),
    (W, "dfsph_r"),
];
/// The divergence-free solve's start.
pub static DIVERGENCE_START: GpuPass = particles("dfsph.cg_divergence_start", START, "divergence", START_BINDINGS);
/// The constant-density solve's start.
pub static DENSITY_START: GpuPass = particles("dfsph.cg_density_start", START, "density", START_BINDINGS);

const ADJUST: &str = particle_kernel!("cg/adjust.wgsl");
const ADJUST_BINDINGS: &[(Access, &str)] = &[
    (U, "params"),
    (U, "dt"),
    (R, "dfsph_scalars"),
    (R, "x"),
    (R, "rho"),
    (R, "alpha"),
    (R, "dfsph_held"),
    (W, "dfsph_r"),
    (W, "dfsph_p"),
];
/// The divergence-free solve's adjusted start.
pub static DIVERGENCE_ADJUST: GpuPass = particles("dfsph.cg_divergence_adjust", ADJUST, "divergence", ADJUST_BINDINGS);
/// The constant-density solve's adjusted start.
pub static DENSITY_ADJUST: GpuPass = particles("dfsph.cg_density_adjust", ADJUST, "density", ADJUST_BINDINGS);

const RESIDUAL: &str = particle_kernel!("cg/residual.wgsl");
/// The divergence-free solve's dot-product terms and residual.
pub static DIVERGENCE_RESIDUAL: GpuPass = particles(
    "dfsph.cg_divergence_residual",
    RESIDUAL,
    "main",
    &[(U, "params"), (U, "dt"), (R, "x"), (R, "alpha"), (R, "dfsph_r"), (W, "dfsph_dot"), (W, "divergence_error")],
);
/// The constant-density solve's dot-product terms and residual.
pub static DENSITY_RESIDUAL: GpuPass = particles(
    "dfsph.cg_density_residual",
    RESIDUAL,
    "main",
    &[(U, "params"), (U, "dt"), (R, "x"), (R, "alpha"), (R, "dfsph_r"), (W, "dfsph_dot"), (W, "density_error")],
);

const UPDATE: &str = particle_kernel!("cg/update.wgsl");
/// The divergence-free solve's step.
pub static DIVERGENCE_UPDATE: GpuPass = particles(
    "dfsph.cg_divergence_update",
    UPDATE,
    "main",
    &[
        (U, "params"),
        (U, "dt"),
        (R, "dfsph_scalars"),
        (R, "dfsph_p"),
        (R, "dfsph_gp"),
        (R, "dfsph_ap"),
        (W, "v"),
        (W, "kappa_v"),
        (W, "dfsph_r"),
    ],
);
/// The constant-density solve's step.
pub static DENSITY_UPDATE: GpuPass = particles(
    "dfsph.cg_density_update",
    UPDATE,
    "main",
    &[
        (U, "params"),
        (U, "dt"),
        (R, "dfsph_scalars"),
        (R, "dfsph_p"),
        (R, "dfsph_gp"),
        (R, "dfsph_ap"),
        (W, "v"),
        (W, "kappa"),
        (W, "dfsph_r"),
    ],
);

const CLAMP: &str = particle_kernel!("cg/clamp.wgsl");
/// The divergence-free solve's clamp.
pub static DIVERGENCE_CLAMP: GpuPass = particles(
    "dfsph.cg_divergence_clamp",
    CLAMP,
    "main",
    &[(U, "params"), (R, "dfsph_scalars"), (R, "kappa_v"), (W, "dkappa_v")],
);
/// The constant-density solve's clamp.
pub static DENSITY_CLAMP: GpuPass = particles(
    "dfsph.cg_density_clamp",
    CLAMP,
    "main",
    &[(U, "params"), (R, "dfsph_scalars"), (R, "kappa"), (W, "dkappa")],
);

/// `G p`.
pub static GRADIENT: GpuPass = particles(
    "dfsph.cg_gradient",
    walk_kernel!("cg/gradient.wgsl"),
    "main",
    &[(U, "params"), (U, "dfsph"), (R, "x"), (R, "starts"), (R, "walls"), (R, "dfsph_p"), (W, "dfsph_gp")],
);
/// `A p` and the terms of `p.Ap`.
pub static PRODUCT: GpuPass = particles(
    "dfsph.cg_product",
    walk_kernel!("cg/product.wgsl"),
    "main",
    &[
        (U, "params"),
        (U, "dfsph"),
        (R, "x"),
        (R, "starts"),
        (R, "walls"),
        (R, "dfsph_gp"),
        (R, "dfsph_p"),
        (R, "dfsph_held"),
        (W, "dfsph_ap"),
        (W, "dfsph_dot"),
    ],
);
/// The next direction.
pub static DIRECTION: GpuPass = particles(
    "dfsph.cg_direction",
    particle_kernel!("cg/direction.wgsl"),
    "main",
    &[(U, "params"), (R, "dfsph_scalars"), (R, "alpha"), (R, "dfsph_r"), (W, "dfsph_p")],
);
