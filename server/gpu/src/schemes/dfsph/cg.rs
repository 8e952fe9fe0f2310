//! DFSPH's conjugate-gradient solves on the GPU: the passes of floe-engine
//! `schemes::dfsph::cg`, one kernel each (both solves share a kernel, by entry point
//! or by bindings); the sums between them stay on the device (`dfsph_scalars`).

use crate::pass::{GpuPass, always};
use crate::passes::{particle_kernel, walk_kernel};
use crate::program::Access::{self, Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::schemes::dfsph::DfsphConsts;
use floe_engine::schemes::dfsph::cg::{
    CLOSED_SPACE, RAW_EXCESS, SHIFT_ANTI_CLUSTERING, SHIFT_LIMIT, SHIFT_MOST, SURFACE_GRADIENT,
};
use floe_engine::schemes::dfsph::spec::DfsphSolver;

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
    walk_kernel!("cg/held.wgsl"),
    "main",
    &[
        (U, "params"),
        (U, "dfsph"),
        (U, "dfsph.cg"),
        (R, "x"),
        (R, "rho"),
        (R, "starts"),
        (R, "walls"),
        (W, "dfsph_held"),
        (R, "dfsph_closed"),
    ],
);

/// At the first step, whether the scene is closed.
pub static CLOSED: GpuPass = GpuPass {
    name: "dfsph.cg_closed",
    source: particle_kernel!("cg/closed.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (R, "dfsph_scalars"), (W, "dfsph_closed")],
    space: CLOSED_SPACE,
    when: always,
};

/// Each particle's shift in a closed scene.
pub static SHIFT: GpuPass = particles(
    "dfsph.cg_shift",
    walk_kernel!("cg/shift.wgsl"),
    "main",
    &[(U, "params"), (U, "dt"), (U, "dfsph.cg"), (R, "x"), (R, "starts"), (R, "walls"), (W, "dfsph_shift")],
);

/// The particles moved by their shifts.
pub static SHIFT_APPLY: GpuPass = particles(
    "dfsph.cg_shift_apply",
    particle_kernel!("cg/shift_apply.wgsl"),
    "main",
    &[(U, "params"), (R, "dfsph_shift"), (W, "x")],
);

/// The uniform's bytes (`dfsph.cg`, counted as the scheme's; `dfsph_cg` in the
/// kernels: x the rest-volume gradient sum, 1/m, at which an under-dense particle is
/// held, y the share of a particle's own density deviation a closed domain's density
/// solve takes, z and w the shift's `shift h` (m) and largest coefficient
/// `SHIFT_MOST h^2` (m^2); then its limit (m), anti-clustering weight and `W(dx)`,
/// which only shift.wgsl reads), when the scene's DFSPH solves by CG.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if model.scheme.id != "dfsph" {
        return None;
    }
    let settings = model.consts::<DfsphConsts>().settings;
    (settings.solver == DfsphSolver::Cg).then(|| {
        let (dx, h) = (model.spacing, 0.5 * model.kernel.support());
        let values = [
            SURFACE_GRADIENT / model.kernel.support(),
            RAW_EXCESS,
            settings.shift * h,
            SHIFT_MOST * h * h,
            SHIFT_LIMIT * dx,
            SHIFT_ANTI_CLUSTERING,
            model.kernel.w_r2(dx * dx),
            0.0,
        ];
        bytemuck::bytes_of(&values).to_vec()
    })
}

/// The walls' hydrostatic pressure.
pub static WALL_PRESSURE: GpuPass = particles(
    "dfsph.cg_wall_pressure",
    walk_kernel!(walls_only; "cg/wall_pressure.wgsl"),
    "main",
    &[
        (U, "params"),
        (U, "dt"),
        (R, "dfsph_scalars"),
        (R, "x"),
        (R, "kappa"),
        (R, "kappa_v"),
        (R, "starts"),
        (R, "walls"),
        (W, "v"),
    ],
);

const WARM: &str = particle_kernel!("cg/warm.wgsl");
const START: &str = particle_kernel!("rate.wgsl", "cg/start.wgsl");
const START_BINDINGS: &[(Access, &str)] = &[
    (U, "params"),
    (U, "dt"),
    (U, "dfsph"),
    (U, "dfsph.cg"),
    (R, "dfsph_scalars"),
    (R, "x"),
    (R, "v"),
    (R, "rho"),
    (R, "starts"),
    (R, "walls"),
    (R, "dfsph_held"),
    (W, "dfsph_r"),
];
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
const RESIDUAL: &str = particle_kernel!("cg/residual.wgsl");
const UPDATE: &str = particle_kernel!("cg/update.wgsl");
const CLAMP: &str = particle_kernel!("cg/clamp.wgsl");

/// One solve's passes: its warm start, start, adjusted start, residual, step and
/// clamp, over its stiffness, increment and residual attributes (the start and the
/// adjusted start take the solve's entry point).
macro_rules! solve_passes {
    ($warm:ident, $start:ident, $adjust:ident, $residual:ident, $update:ident, $clamp:ident, $solve:literal,
     $kappa:literal, $increment:literal, $error:literal) => {
        #[doc = concat!("The ", $solve, " solve's warm start.")]
        pub static $warm: GpuPass = particles(
            concat!("dfsph.cg_", $solve, "_warm"),
            WARM,
            "main",
            &[(U, "params"), (U, "dfsph"), (R, "dfsph_scalars"), (W, $kappa), (W, $increment), (R, "dfsph_held")],
        );
        #[doc = concat!("The ", $solve, " solve's start.")]
        pub static $start: GpuPass = particles(concat!("dfsph.cg_", $solve, "_start"), START, $solve, START_BINDINGS);
        #[doc = concat!("The ", $solve, " solve's adjusted start.")]
        pub static $adjust: GpuPass =
            particles(concat!("dfsph.cg_", $solve, "_adjust"), ADJUST, $solve, ADJUST_BINDINGS);
        #[doc = concat!("The ", $solve, " solve's dot-product terms and residual.")]
        pub static $residual: GpuPass = particles(
            concat!("dfsph.cg_", $solve, "_residual"),
            RESIDUAL,
            "main",
            &[(U, "params"), (U, "dt"), (R, "x"), (R, "alpha"), (R, "dfsph_r"), (W, "dfsph_dot"), (W, $error)],
        );
        #[doc = concat!("The ", $solve, " solve's step.")]
        pub static $update: GpuPass = particles(
            concat!("dfsph.cg_", $solve, "_update"),
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
                (W, $kappa),
                (W, "dfsph_r"),
            ],
        );
        #[doc = concat!("The ", $solve, " solve's clamp.")]
        pub static $clamp: GpuPass = particles(
            concat!("dfsph.cg_", $solve, "_clamp"),
            CLAMP,
            "main",
            &[(U, "params"), (R, "dfsph_scalars"), (R, $kappa), (W, $increment)],
        );
    };
}

solve_passes!(
    DIVERGENCE_WARM,
    DIVERGENCE_START,
    DIVERGENCE_ADJUST,
    DIVERGENCE_RESIDUAL,
    DIVERGENCE_UPDATE,
    DIVERGENCE_CLAMP,
    "divergence",
    "kappa_v",
    "dkappa_v",
    "divergence_error"
);
solve_passes!(
    DENSITY_WARM,
    DENSITY_START,
    DENSITY_ADJUST,
    DENSITY_RESIDUAL,
    DENSITY_UPDATE,
    DENSITY_CLAMP,
    "density",
    "kappa",
    "dkappa",
    "density_error"
);

/// `G p`.
pub static GRADIENT: GpuPass = particles(
    "dfsph.cg_gradient",
    walk_kernel!("gradient_sum.wgsl", "cg/gradient.wgsl"),
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
