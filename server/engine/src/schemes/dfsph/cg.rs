//! DFSPH's two solves by preconditioned conjugate gradients
//! (`solver.dfsph.solver = "cg"`), in place of B&K's Jacobi iteration, which
//! diverges on closed and periodic flows (docs/validation/schemes/NOTES.md, "Why
//! DFSPH fails on closed and periodic flows") and cannot hold mirrored walls.
//!
//! With the stiffness `P = p / rho^2` and the kick `v -= dt G P`, where
//! `(G P)_i = sum_j (m_i P_i + m_j^2 P_j / m_i) grad W_ij + c P_i sum_b psi_b grad W_ib`
//! and the compression rate
//! `(D v)_i = m_i sum_j (v_i - v_j) . grad W_ij + c sum_b psi_b v_i . grad W_ib`,
//! a kick by `P` lowers the predicted compression by `dt^2 D G P`, so both solves
//! are `A P = b` with `A = D G`: for the constant-density solve
//! `b = (rho + dt D v - rho0) / dt^2`, for the divergence-free solve `b = D v / dt`.
//! For particles of one mass `D = G^T / m`, so `A` is symmetric positive
//! semi-definite and conjugate gradients apply (Saad 2003, "Iterative methods for
//! sparse linear systems", algorithm 9.1, with the Jacobi preconditioner
//! `1 / A_ii`, which is B&K's factor `alpha`). A scene of several masses is refused.
//!
//! The walls are mirrored (`c = 2`): a wall particle takes the pressure of the fluid
//! particle it faces, and the density rate counts it as the mirror image moving at
//! `-v_i`, which keeps `A` symmetric. Akinci's one-sided term (`c = 1`, the Jacobi's)
//! needs about twice the hydrostatic pressure beside a wall; mirrored, wall and
//! interior agree (docs/validation/schemes/CG.md, where every choice below was
//! measured on a prototype). On top of the mirror, the wall particle carries the
//! fluid's hydrostatic pressure difference (Adami, Hu & Adams 2012, J. Comput. Phys.
//! 231, eq. 27, with the facing particle's pressure for the fluid's weighted mean and
//! walls at rest): `P_b = P_i + g . (x_b - x_i) / rho0_i`, at a free surface no less
//! than zero (`P_i` the particle's last stiffnesses, `kappa + kappa_v`). The second
//! term does not depend on the unknown, so `A` keeps its symmetry: the pass
//! `dfsph.cg_wall_pressure` applies its force as a kick, once a step, before the
//! constant-density solve. Without it the mirror holds a column at 1.09 of
//! hydrostatic (the floor and the side walls give no pressure gradient); with it the
//! column at 0.025 m came to pressure L2 0.041 against 0.097, the dam break's front
//! to 0.22 against 0.43 and Poiseuille to 0.0038 against 0.0068 (CG.md; 0.026 and
//! 0.12 for the first two since the start below).
//!
//! What the solves do beyond plain CG, and why:
//! - particles with fewer than [`super::FULL_NEIGHBOURHOOD`] neighbours, a summed
//!   density below [`SURFACE_DENSITY`] of rest, or below rest with a neighbourhood a
//!   free surface cuts ([`SURFACE_GRADIENT`]) are held at `P = 0` (their rows and
//!   columns removed): a free surface;
//! - with no particle held (a closed or periodic domain) the starting residual's mean
//!   is removed: a uniform stiffness moves nothing there (the near-null mode), and
//!   the mean compression that the particles' disorder adds to a summed density
//!   cannot be solved for;
//! - with a free surface, the density solve starts from `max(rho, rho0)` (as IISPH
//!   and SPlisHSPlasH do: a deficient density near the surface would ask for
//!   tension), and after each solve its stiffness is clamped at zero, applied as a
//!   kick by the difference (a negative `P` beside a one-sided wall pulls the fluid
//!   into it);
//! - each solve starts from its last stiffness: all of it where a free surface
//!   exists, [`super::WARM_START`] (one half) in a closed domain, none for a held
//!   particle (its stiffness is zero, not the last one it had while free; a fluid's
//!   vertical face otherwise kept the hydrostatic start below). The first density
//!   solve starts from the weight of the fluid above each particle
//!   ([`crate::overburden`]), not from zero. At a free surface
//!   a solve stopped at its tolerance does not pin the pressure (`A` is nearly
//!   singular on smooth modes) and the carried stiffness is what holds it (the
//!   resting column at 0.025 m: pressure L2 0.78 with one half). In a closed domain
//!   the near-null modes, which CG does not correct, would build up from step to
//!   step with all of it (Poiseuille halts; 0.0068 with one half).
//!
//! A scene is closed or open once and for all at its first step (`dfsph_closed`, a
//! state saved with snapshots): closed if no particle is held then. The held test
//! is not run again in a closed scene: in a disordered bulk its surface criteria
//! misfire on single particles (a summed density under [`SURFACE_DENSITY`], a
//! rest-volume gradient sum over [`SURFACE_GRADIENT`]), and one held particle
//! turned the whole periodic vortex into an open domain for a step (the mean kept,
//! the stiffness clamped): the vortex under the shift below halted at step 27
//! (docs/validation/schemes/CG.md).
//!
//! In a closed scene the particles are shifted after each drift
//! (`solver.dfsph.shift`, [`SHIFT_MOST`], [`SHIFT_ANTI_CLUSTERING`], [`SHIFT_LIMIT`]):
//! `dx_i = -D sum_j V_j (1 + R (W_ij / W(dx))^4) grad W_ij`, with the walls' rest
//! volumes `psi_b / rho0_i`, from the positions the drift left (the neighbours from
//! the step's grid), at most [`SHIFT_LIMIT`] spacings. It is Lind, Xu, Stansby &
//! Rogers's Fickian shift (2012, J. Comput. Phys. 231, `dr = -D grad C` with their
//! anti-clustering term, Monaghan's tensile correction on the concentration's
//! gradient), with the coefficient of Sun, Colagrossi, Marrone & Zhang's
//! delta-plus-SPH (2017, Comput. Methods Appl. Mech. Eng. 315), `CFL Ma (2h)^2`,
//! which is `4 h U dt` for the flow's largest speed `U`: `D = shift h v_max dt`, at
//! most [`SHIFT_MOST`] `h^2` (the shift is stable to about 0.7 `h^2` a step on the
//! vortex). `D` follows the flow's displacement, not the step: the density solve
//! answers a shift's compression with a velocity of the shift over `dt`, and a
//! shift of a fixed size each step drove the Poiseuille channel (its step 0.25 ms,
//! the viscous limit) unstable within 30 steps.
//!
//! Why: a Lagrangian arrangement cannot follow a vortex at constant summed density.
//! The exact Taylor-Green flow carries a lattice into layers whose summed density
//! spreads to 2.4 times rest by 0.28 s, and the constant-density solve answers that
//! spread with pressures the flow does not have, which drained the vortex 57 % too
//! fast at 1/40 m. The shift keeps the arrangement isotropic so that there is
//! little for the solve to correct: the vortex within 0.5 % at 1/40 m
//! (docs/validation/schemes/CG.md). Velocities are not corrected for the shift
//! (Lind et al.'s Taylor expansion measured no better). Free surfaces are not
//! shifted (the concentration gradient there points out of the fluid).
//!
//! The residual checked is the mean of `|r| dt^2 / rho0` (the signed counterpart of
//! the Jacobi's mean compression), against the same tolerances.
//!
//! Passes (stage `Solve`; the sums between them stay on the device, in
//! `dfsph_scalars`), for the density solve (the divergence solve's have
//! `divergence` in their names):
//! 0. once a step, before its length is chosen: `dfsph.cg_held` (`HELD` summed),
//!    `dfsph.cg_closed` (at the first step, whether the scene is closed);
//!    before the constant-density solve: `dfsph.cg_wall_pressure`;
//! 1. `dfsph.cg_density_warm` and the Jacobi's kick (the warm start),
//!    `dfsph.cg_density_start`: `r = b` (`RSUM` summed; in a closed domain with the
//!    density's deviation filtered, [`RAW_EXCESS`]);
//! 2. `dfsph.cg_density_adjust`: the mean removed or the surface's density clamped,
//!    `p = alpha r`;
//! 3. `dfsph.cg_density_residual`: per particle `r alpha r` (summed into `RZ`) and
//!    the residual;
//! 4. per iteration: `dfsph.cg_gradient` (`G p`), `dfsph.cg_product` (`A p = D G p`,
//!    `p . Ap` summed into `PAP`), `dfsph.cg_density_update` (`a = RZ / PAP`,
//!    `P += a p`, `v -= dt a G p`, `r -= a A p`), `dfsph.cg_density_residual`
//!    (summed into `RZ_NEW`), `dfsph.cg_direction` (`p = alpha r + (RZ_NEW / RZ) p`,
//!    then `RZ = RZ_NEW`);
//! 5. after the solve: `dfsph.cg_density_clamp` and the Jacobi's kick;
//! 6. after the drift, in a closed scene with a shift: `dfsph.cg_shift` (each
//!    particle's displacement) and `dfsph.cg_shift_apply` (the particles moved).

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::plan::PassSpec;
use crate::scheme::{Iterate, Op, ReduceOp, Reduction};

use super::spec::DfsphSettings;

/// A particle whose summed density is below this fraction of its rest density is
/// held at `P = 0` (a free surface), as one with too few neighbours is. The
/// neighbour count alone misses the top layer of a resting column (up to 26
/// neighbours once slightly compressed), whose summed density is about 0.965 of
/// rest; the layer below sums to 0.995 or more. Counted alone, the whole column was
/// taken for a closed domain at some steps (pressure L2 0.098 to 0.17 depending on
/// this choice: docs/validation/schemes/CG.md).
pub const SURFACE_DENSITY: f32 = 0.97;

/// A particle below its rest density whose rest-volume gradient sum `|sum_j V_j grad
/// W_ij + sum_b V_b grad W_ib|` ([`super::cpu::Sums::volume_gradient`]) times the
/// kernel's support is at least this is held at `P = 0` too. The sum vanishes in a
/// full neighbourhood, compressed or not, and a free surface cuts it: on a resting
/// column at 0.025 m the top layer sums to 0.8-1.0, the layer below to 0.22 at
/// most, the interior to 0.05. [`SURFACE_DENSITY`] alone lets a settled top layer
/// go free once it is pressed to 0.97-0.98 of rest: with no particle held the solves
/// took the column for a closed domain, whose pressure level they do not pin, and
/// the column burst after 1.8 s (docs/validation/schemes/CG.md). A compressed
/// particle is never held by this test: at P = 0 beside a wall (whose pressure
/// mirrors the particle's) nothing would stop it being pressed into the wall.
pub const SURFACE_GRADIENT: f32 = 0.5;

/// In a closed domain (no particle held) the constant-density solve corrects the
/// summed density's deviation `rho - rho0` as its Shepard mean over the fluid
/// neighbours, `sum_j W_ij (rho_j - rho0) / sum_j W_ij`, plus this share of the
/// particle's own difference from that mean. The deviation has parts no pressure can
/// correct (outside the range of `A`: an alternating pattern on a periodic lattice),
/// and the solves drift along them: the heated channel grew such a pressure mode
/// about 2 % a step from 0.7 s (velocity L2 2.4; 0.0042 filtered). The mean alone
/// leaves short-wavelength compression uncorrected (the Taylor-Green vortex at 1/60 m
/// halted); with a tenth it halted at 1.49 s, with three tenths it runs (decay error
/// 0.30 there, 0.57 at 1/40 m, against 0.49 and 0.81 unfiltered;
/// docs/validation/schemes/CG.md).
pub const RAW_EXCESS: f32 = 0.3;

/// The anti-clustering weight `R` of the shift: measured on the Taylor-Green vortex
/// at 1/40 m with a fixed coefficient of 0.44 `h^2` a step (decay rate error 0.0197
/// at 0.2, Lind et al.'s value; 0.0004 at 0.5; 0.0038 at 1; 0.074 without the term).
pub const SHIFT_ANTI_CLUSTERING: f32 = 0.5;

/// The largest coefficient `D` of the shift in one step, in `h^2` (`h` half the
/// support): the vortex halts at 0.9 and runs at 0.67 (a fixed coefficient each
/// step, measured on the CPU).
pub const SHIFT_MOST: f32 = 0.45;

/// The largest shift of a particle in one step, in spacings.
pub const SHIFT_LIMIT: f32 = 0.1;

/// [`CLOSED`]'s value before the first step.
pub const UNDECIDED: f32 = 0.0;
/// [`CLOSED`]'s value in a closed scene.
pub const IS_CLOSED: f32 = 1.0;
/// [`CLOSED`]'s value in an open scene (a free surface at the first step).
pub const IS_OPEN: f32 = 2.0;

/// The space of the scene's closed-or-open decision (one element).
pub const CLOSED_SPACE: &str = "dfsph.closed";

/// The space of the solves' scalars.
pub const SPACE: &str = "dfsph.cg";
/// Slots of `dfsph_scalars`: `r.z` (the current one), `p.Ap`, the new `r.z`, the
/// number of held particles, the sum of the starting residual.
pub const RZ: u32 = 0;
/// See [`RZ`].
pub const PAP: u32 = 1;
/// See [`RZ`].
pub const RZ_NEW: u32 = 2;
/// See [`RZ`].
pub const HELD: u32 = 3;
/// See [`RZ`].
pub const RSUM: u32 = 4;
/// Slots in all.
pub const SLOTS: usize = 5;

const fn attr(name: &'static str, elem: Elem, unit: &'static str, about: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role: Role::Derived, added_later: false, space: PARTICLES, module: "dfsph", about }
}

/// The residual `b - A P`.
pub static R: AttrSpec = attr("dfsph_r", Elem::F32, "kg/(m^3 s^2)", "DFSPH CG: the residual.");
/// The search direction.
pub static P: AttrSpec = attr("dfsph_p", Elem::F32, "m^5/(kg s^2)", "DFSPH CG: the search direction.");
/// `G p`, the acceleration a unit step along `p` gives.
pub static GP: AttrSpec = attr("dfsph_gp", Elem::Vec3, "m/s^2", "DFSPH CG: the pressure acceleration of p.");
/// `A p = D G p`.
pub static AP: AttrSpec = attr("dfsph_ap", Elem::F32, "kg/(m^3 s^2)", "DFSPH CG: the matrix times p.");
/// Each particle's term of the dot product summed next.
pub static DOT: AttrSpec = attr("dfsph_dot", Elem::F32, "", "DFSPH CG: dot-product terms.");
/// 1 for a particle held at `P = 0` (a free surface), else 0.
pub static HELD_ATTR: AttrSpec = attr("dfsph_held", Elem::F32, "", "DFSPH CG: 1 where held at zero pressure.");
/// The solves' scalars.
pub static SCALARS: AttrSpec = AttrSpec {
    name: "dfsph_scalars",
    elem: Elem::F32,
    unit: "",
    role: Role::Derived,
    added_later: false,
    space: SPACE,
    module: "dfsph",
    about: "DFSPH CG: r.z, p.Ap, the new r.z, held particles and the starting residual's sum.",
};

/// Whether the scene is closed: [`UNDECIDED`] until the first step's held test,
/// then [`IS_CLOSED`] (no particle held) or [`IS_OPEN`].
pub static CLOSED: AttrSpec = AttrSpec {
    name: "dfsph_closed",
    elem: Elem::F32,
    unit: "",
    role: Role::State,
    added_later: true,
    space: CLOSED_SPACE,
    module: "dfsph",
    about: "DFSPH CG: 0 before the first step, then 1 in a closed scene, 2 in an open one.",
};

/// Each particle's shift this step (m).
pub static SHIFT: AttrSpec = attr("dfsph_shift", Elem::Vec3, "m", "DFSPH CG: the particle's shift this step.");

/// Every attribute of the solves.
pub const ATTRS: [&AttrSpec; 7] = [&R, &P, &GP, &AP, &DOT, &HELD_ATTR, &SCALARS];

macro_rules! solve_passes {
    ($warm:ident, $start:ident, $adjust:ident, $residual:ident, $update:ident, $clamp:ident, $solve:literal, $kappa:literal,
     $increment:literal, $error:literal) => {
        /// The warm start: `increment = w kappa`, `kappa = 0`.
        pub static $warm: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_warm"),
            &["dfsph_scalars", "dfsph_held", $kappa],
            &[$increment, $kappa],
            &[],
        );
        /// `r = b` (0 where held).
        pub static $start: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_start"),
            &["dfsph_scalars", "x", "v", "rho", "dfsph_held"],
            &["dfsph_r"],
            &[],
        );
        /// The mean removed (closed) or the surface's density clamped; `p = alpha r`.
        pub static $adjust: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_adjust"),
            &["dfsph_scalars", "x", "rho", "alpha", "dfsph_held"],
            &["dfsph_p"],
            &["dfsph_r"],
        );
        /// Each particle's `r alpha r` and residual.
        pub static $residual: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_residual"),
            &["x", "alpha", "dfsph_r"],
            &["dfsph_dot", $error],
            &[],
        );
        /// The step along `p`.
        pub static $update: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_update"),
            &["dfsph_scalars", "dfsph_p", "dfsph_gp", "dfsph_ap"],
            &[],
            &["v", $kappa, "dfsph_r"],
        );
        /// The increment that clamps the stiffness at zero where a free surface exists.
        pub static $clamp: PassSpec = PassSpec::solve(
            "dfsph",
            concat!("dfsph.cg_", $solve, "_clamp"),
            &["dfsph_scalars", $kappa],
            &[$increment],
            &[],
        );
    };
}

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

/// The particles held at `P = 0`: a free surface ([`SURFACE_DENSITY`],
/// [`SURFACE_GRADIENT`]; run
/// once a step, before its length is chosen; both solves have the same neighbours).
pub static HELD_PASS: PassSpec =
    PassSpec::solve("dfsph", "dfsph.cg_held", &["x", "rho", "dfsph_closed"], &["dfsph_held"], &[]);
/// At the first step, whether the scene is closed (no particle held).
pub static CLOSED_PASS: PassSpec =
    PassSpec::solve("dfsph", "dfsph.cg_closed", &["dfsph_scalars"], &[], &["dfsph_closed"]);
/// Each particle's shift from the positions the drift left.
pub static SHIFT_PASS: PassSpec = PassSpec::solve("dfsph", "dfsph.cg_shift", &["x"], &["dfsph_shift"], &[]);
/// The particles moved by their shifts (back through a periodic face).
pub static SHIFT_APPLY: PassSpec = PassSpec::solve("dfsph", "dfsph.cg_shift_apply", &["dfsph_shift"], &[], &["x"]);
/// The walls' hydrostatic pressure, as a kick before the constant-density solve
/// (once a step; see the module's documentation).
pub static WALL_PRESSURE_PASS: PassSpec =
    PassSpec::solve("dfsph", "dfsph.cg_wall_pressure", &["dfsph_scalars", "x", "kappa", "kappa_v"], &[], &["v"]);
/// `G p`.
pub static GRADIENT: PassSpec = PassSpec::solve("dfsph", "dfsph.cg_gradient", &["x", "dfsph_p"], &["dfsph_gp"], &[]);
/// `A p = D G p` (0 for held particles) and the terms of `p . Ap`.
pub static PRODUCT: PassSpec = PassSpec::solve(
    "dfsph",
    "dfsph.cg_product",
    &["x", "dfsph_gp", "dfsph_p", "dfsph_held"],
    &["dfsph_ap", "dfsph_dot"],
    &[],
);
/// The next direction.
pub static DIRECTION: PassSpec =
    PassSpec::solve("dfsph", "dfsph.cg_direction", &["dfsph_scalars", "alpha", "dfsph_r"], &[], &["dfsph_p"]);

/// Every pass of the solves (the Jacobi's kicks too), in the order each first runs.
pub const PASSES: [&PassSpec; 20] = [
    &HELD_PASS,
    &CLOSED_PASS,
    &DIVERGENCE_WARM,
    &super::DIVERGENCE_KICK,
    &DIVERGENCE_START,
    &DIVERGENCE_ADJUST,
    &DIVERGENCE_RESIDUAL,
    &GRADIENT,
    &PRODUCT,
    &DIVERGENCE_UPDATE,
    &DIRECTION,
    &DIVERGENCE_CLAMP,
    &WALL_PRESSURE_PASS,
    &DENSITY_WARM,
    &super::DENSITY_KICK,
    &DENSITY_START,
    &DENSITY_ADJUST,
    &DENSITY_RESIDUAL,
    &DENSITY_UPDATE,
    &DENSITY_CLAMP,
];

const fn sum(attr: &'static str, slot: u32) -> Op {
    Op::Sum { attr, into: "dfsph_scalars", slot }
}

macro_rules! iteration {
    ($solve:literal) => {
        &[
            Op::Pass("dfsph.cg_gradient"),
            Op::Pass("dfsph.cg_product"),
            sum("dfsph_dot", PAP),
            Op::Pass(concat!("dfsph.cg_", $solve, "_update")),
            Op::Pass(concat!("dfsph.cg_", $solve, "_residual")),
            sum("dfsph_dot", RZ_NEW),
            Op::Pass("dfsph.cg_direction"),
            sum("dfsph_dot", RZ),
        ]
    };
}

macro_rules! start {
    ($solve:literal $(, $first:expr)*) => {
        &[
            $($first,)*
            Op::Pass(concat!("dfsph.cg_", $solve, "_warm")),
            Op::Pass(concat!("dfsph.", $solve, "_kick")),
            Op::Pass(concat!("dfsph.cg_", $solve, "_start")),
            sum("dfsph_r", RSUM),
            Op::Pass(concat!("dfsph.cg_", $solve, "_adjust")),
            Op::Pass(concat!("dfsph.cg_", $solve, "_residual")),
            sum("dfsph_dot", RZ),
        ]
    };
}

/// What runs after the divergence-free solve: the clamp and its kick.
pub const DIVERGENCE_FINISH: &[Op] = &[Op::Pass("dfsph.cg_divergence_clamp"), Op::Pass("dfsph.divergence_kick")];
/// What runs after the constant-density solve.
pub const DENSITY_FINISH: &[Op] = &[Op::Pass("dfsph.cg_density_clamp"), Op::Pass("dfsph.density_kick")];

fn solve(
    name: &'static str,
    start: &'static [Op],
    iteration: &'static [Op],
    residual: &'static str,
    tolerance: f32,
    max: u32,
) -> Iterate {
    Iterate {
        name,
        start,
        iteration,
        residual: Reduction { attr: residual, op: ReduceOp::Mean },
        tolerance: f64::from(tolerance),
        min: 1,
        max,
        check_every: 1,
        sweeps: 1,
        max_sweeps: 1,
    }
}

/// What runs once a step before its length is chosen (the step's pressure limit
/// reads the count): the held particles, counted into `HELD`, and at the first
/// step the scene's closed-or-open decision.
pub const HELD_OPS: &[Op] = &[Op::Pass("dfsph.cg_held"), sum("dfsph_held", HELD), Op::Pass("dfsph.cg_closed")];
/// The shift's passes: after the drift, in a closed scene.
pub const SHIFT_OPS: &[Op] = &[Op::Pass("dfsph.cg_shift"), Op::Pass("dfsph.cg_shift_apply")];
/// The shift's passes and attribute, built with a CG whose `shift` is not zero.
pub const SHIFT_PASSES: [&PassSpec; 2] = [&SHIFT_PASS, &SHIFT_APPLY];
const DIVERGENCE_START_OPS: &[Op] = start!("divergence");
const DIVERGENCE_ITERATION: &[Op] = iteration!("divergence");
const DENSITY_START_OPS: &[Op] = start!("density", Op::Pass("dfsph.cg_wall_pressure"));
const DENSITY_ITERATION: &[Op] = iteration!("density");

/// The divergence-free solve (named as the Jacobi's, so reports compare them).
pub fn divergence_solve(s: &DfsphSettings) -> Iterate {
    solve(
        "dfsph.divergence",
        DIVERGENCE_START_OPS,
        DIVERGENCE_ITERATION,
        "divergence_error",
        s.divergence_tolerance,
        s.max_iterations,
    )
}

/// The constant-density solve.
pub fn density_solve(s: &DfsphSettings) -> Iterate {
    solve("dfsph.density", DENSITY_START_OPS, DENSITY_ITERATION, "density_error", s.density_tolerance, s.max_iterations)
}

/// `a / b`, or 0 where `b` is not positive (nothing left to solve).
#[inline(always)]
pub fn ratio(a: f32, b: f32) -> f32 {
    if b > 0.0 { a / b } else { 0.0 }
}
