//! Implicit viscosity (the [`super::ViscousSolver::Implicit`] the module that sets the
//! per-particle viscosity chooses, such as `snow.solver`): the viscous force of
//! [`super`] integrated by backward Euler after each kick, as Weiler,
//! Koschier, Brand & Bender (2018, "A physically consistent implicit viscosity
//! solver for SPH fluids", Computer Graphics Forum 37(2)) do for theirs, so stiff
//! viscosities (mu_0 / mu_inf of 1e4 and more) run at the pressure-limited dt.
//!
//! With the velocities `v*` of the kick and the viscosities `mu` of the step's
//! evaluation (frozen for the solve: one Picard step per time step, as Weiler et al.),
//! the new velocities solve
//!
//! `(M + dt K) v = M v*`, where `(K v)_i = sum_j w_ij (v_i - v_j) + w_iw v_i`,
//!
//! `w_ij = s m_i m_j (mu_i + mu_j) / (rho_i rho_j) |F_ij|` (the explicit pass's pair
//! term times `m_i`, symmetric, with its lattice normalisation s) and `w_iw` the
//! no-slip walls' mirror term `s m_i 4 mu_i / rho_i^2 sum_b psi_b |F_ib|` (0 for slip
//! walls). The matrix is
//! symmetric and positive definite (M positive, K a weighted graph Laplacian plus a
//! non-negative diagonal), so conjugate gradients converge; the preconditioner is
//! its diagonal `d_i = m_i + dt (sum_j w_ij + w_iw)` (Jacobi). The start is `v*`,
//! whose residual `r = M v* - (M + dt K) v* = dt m a` is the explicit force's impulse.
//!
//! Passes (stage `Solve`, run by the solve, [`solve`]) and the sums between them,
//! which stay on the device in `visc_scalars` (`RZ`, `R0Z`, `PAP`, `RZ_NEW`):
//! 1. `viscosity.implicit_diagonal`: `d`, `r`;
//! 2. `viscosity.implicit_precondition`: `p = z = r / d`; per particle `r.z`, summed
//!    into `RZ` and, kept for the convergence test, `R0Z`;
//! 3. per iteration: `viscosity.implicit_product` (`Ap`, `p.Ap` summed into `PAP`),
//!    `viscosity.implicit_update` (`alpha = RZ / PAP`, `v += alpha p`, `r -= alpha Ap`,
//!    `r.z` summed into `RZ_NEW`), `viscosity.implicit_direction`
//!    (`p = z + (RZ_NEW / RZ) p`, then `RZ = RZ_NEW`).
//!
//! The residual is `sqrt(r.z / r0.z)` in the preconditioner's norm: the residual
//! against the start's, the explicit impulse `dt m a`, so the solve reaches the
//! velocity change the viscosity makes in the step to `tolerance`, however small
//! that change is beside the velocities themselves. (Measured against the momentum
//! `m v*` instead, a tolerance of 1e-3 let a solve stop after one iteration where dt
//! is small, at the impulse per step of about 1e-3 of the momentum: the heated
//! channel's profile came out 4 % off at 20 layers, and worse with finer ones.) A
//! flow at rest has `r0 = 0`: its residual is 0 after the one iteration every solve
//! runs.

use super::{MODULE, VaryingViscosity};
use crate::attrs::{AttrSpec, Attrs, Elem, PARTICLES, Role};
use crate::cpu::neighbors::{CHUNK, ChunkNeighbors};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::PassSpec;
use crate::scheme::{Iterate, Op, ReduceOp, Reduction};
use rayon::prelude::*;

/// The space of the solve's scalars.
pub const SCALARS_SPACE: &str = "viscosity.solve";
/// Slots of `visc_scalars`: `r.z` (the current one), `r.z` at the start, `p.Ap`, `r.z` (the new one).
pub const RZ: u32 = 0;
/// See [`RZ`].
pub const R0Z: u32 = 1;
/// See [`RZ`].
pub const PAP: u32 = 2;
/// See [`RZ`].
pub const RZ_NEW: u32 = 3;

const fn attr(name: &'static str, elem: Elem, unit: &'static str, about: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role: Role::Derived, added_later: false, space: PARTICLES, module: MODULE, about }
}

/// The residual `M v* - (M + dt K) v`.
pub static R: AttrSpec = attr("visc_r", Elem::Vec3, "kg m/s", "Implicit viscosity: the residual.");
/// The search direction.
pub static P: AttrSpec = attr("visc_p", Elem::Vec3, "m/s", "Implicit viscosity: the search direction.");
/// The matrix times the search direction.
pub static AP: AttrSpec = attr("visc_ap", Elem::Vec3, "kg m/s", "Implicit viscosity: the matrix times p.");
/// The diagonal `m + dt (sum_j w_ij + w_iw)`.
pub static DIAGONAL: AttrSpec = attr("visc_diag", Elem::F32, "kg", "Implicit viscosity: the matrix diagonal.");
/// Each particle's term of the dot product summed next.
pub static DOT: AttrSpec = attr("visc_dot", Elem::F32, "kg m^2/s^2", "Implicit viscosity: dot-product terms.");
/// Each particle's `r.z / R0Z` (the start leaves `r.z` in it, summed into `R0Z`).
pub static RESIDUAL: AttrSpec = attr("visc_residual", Elem::F32, "", "Implicit viscosity: residual terms.");
/// The solve's scalars.
pub static SCALARS: AttrSpec = AttrSpec {
    name: "visc_scalars",
    elem: Elem::F32,
    unit: "kg m^2/s^2",
    role: Role::Derived,
    added_later: false,
    space: SCALARS_SPACE,
    module: MODULE,
    about: "Implicit viscosity: r.z, r.z at the start, p.Ap and the new r.z, summed on the device.",
};

/// Every attribute of the solve.
pub const ATTRS: [&AttrSpec; 7] = [&R, &P, &AP, &DIAGONAL, &DOT, &RESIDUAL, &SCALARS];

/// `d` and the starting residual `r = dt m a`.
pub static DIAGONAL_PASS: PassSpec =
    PassSpec::solve(MODULE, "viscosity.implicit_diagonal", &["x", "v", "rho", "mu"], &["visc_diag", "visc_r"], &[]);
/// `p = r / d`, the terms of `r.z`.
pub static PRECONDITION: PassSpec = PassSpec::solve(
    MODULE,
    "viscosity.implicit_precondition",
    &["visc_r", "visc_diag"],
    &["visc_p", "visc_dot", "visc_residual"],
    &[],
);
/// `Ap` and the terms of `p.Ap`.
pub static PRODUCT: PassSpec = PassSpec::solve(
    MODULE,
    "viscosity.implicit_product",
    &["x", "rho", "mu", "visc_p", "visc_diag"],
    &["visc_ap", "visc_dot"],
    &[],
);
/// The step along `p`: velocities and residual, the terms of the new `r.z`.
pub static UPDATE: PassSpec = PassSpec::solve(
    MODULE,
    "viscosity.implicit_update",
    &["visc_scalars", "visc_p", "visc_ap", "visc_diag"],
    &["visc_dot", "visc_residual"],
    &["v", "visc_r"],
);
/// The next search direction.
pub static DIRECTION: PassSpec =
    PassSpec::solve(MODULE, "viscosity.implicit_direction", &["visc_scalars", "visc_r", "visc_diag"], &[], &["visc_p"]);

/// Every pass of the solve.
pub const PASSES: [&PassSpec; 5] = [&DIAGONAL_PASS, &PRECONDITION, &PRODUCT, &UPDATE, &DIRECTION];

const fn sum(slot: u32) -> Op {
    Op::Sum { attr: "visc_dot", into: "visc_scalars", slot }
}

/// The start: diagonal, residual, preconditioned direction and the first sums.
const START: &[Op] = &[
    Op::Pass("viscosity.implicit_diagonal"),
    Op::Pass("viscosity.implicit_precondition"),
    sum(RZ),
    Op::Sum { attr: "visc_residual", into: "visc_scalars", slot: R0Z },
];

/// One conjugate-gradient iteration.
const ITERATION: &[Op] = &[
    Op::Pass("viscosity.implicit_product"),
    sum(PAP),
    Op::Pass("viscosity.implicit_update"),
    sum(RZ_NEW),
    Op::Pass("viscosity.implicit_direction"),
    sum(RZ),
];

/// The solve's name (in step reports and statistics).
pub const NAME: &str = "viscosity";

/// The solve at relative residual `tolerance`, with at most `max` iterations.
pub fn solve(tolerance: f32, max: u32) -> Iterate {
    Iterate {
        name: NAME,
        start: START,
        iteration: ITERATION,
        residual: Reduction { attr: "visc_residual", op: ReduceOp::Norm },
        tolerance: f64::from(tolerance),
        min: 1,
        max,
        check_every: 1,
        sweeps: 1,
        max_sweeps: 1,
    }
}

/// `a / b`, or 0 where `b` is not positive (a flow at rest: nothing left to solve).
#[inline(always)]
pub fn ratio(a: Real, b: Real) -> Real {
    if b > 0.0 { a / b } else { 0.0 }
}

/// `viscosity.implicit_diagonal` on the CPU.
#[derive(Debug)]
pub struct Diagonal;
/// `viscosity.implicit_precondition` on the CPU.
#[derive(Debug)]
pub struct Precondition;
/// `viscosity.implicit_product` on the CPU.
#[derive(Debug)]
pub struct Product;
/// `viscosity.implicit_update` on the CPU.
#[derive(Debug)]
pub struct Update;
/// `viscosity.implicit_direction` on the CPU.
#[derive(Debug)]
pub struct Direction;

impl CpuPass for Diagonal {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| diagonal(cx, s))
    }
}

impl CpuPass for Product {
    fn run(&self, cx: &mut CpuCx<'_>) {
        product(cx)
    }
}

/// The material of every particle (none in single-material scenes).
fn materials(attrs: &Attrs) -> Option<&[u32]> {
    attrs.find::<u32>("material").map(|m| attrs.get(m))
}

/// What the pair weights `w_ij` of the step need: positions, densities, viscosities.
struct Pairs<'a, S> {
    sep: S,
    model: &'a crate::model::Model,
    pos: &'a [Vec3],
    rho: &'a [Real],
    mu: &'a [Real],
    material: Option<&'a [u32]>,
    /// `0.01 h^2` (m^2).
    eps_h2: Real,
    /// The lattice normalisation of the pair sum.
    scale: Real,
}

impl<'a, S: Separation> Pairs<'a, S> {
    fn new(sep: S, model: &'a crate::model::Model, attrs: &'a Attrs) -> Self {
        let support = model.kernel.support();
        Self {
            sep,
            model,
            pos: attrs.get(attrs.handle::<Vec3>("x")),
            rho: attrs.get(attrs.handle::<Real>("rho")),
            mu: attrs.get(attrs.handle::<Real>("mu")),
            material: materials(attrs),
            eps_h2: 0.01 * 0.25 * support * support,
            scale: model.consts::<VaryingViscosity>().scale,
        }
    }

    fn mass(&self, i: usize) -> Real {
        self.model.materials.get(self.material.map_or(0, |m| m[i] as usize)).mass
    }

    /// `|F|` at distance `r` (`r2 = r^2 > 0`).
    fn f(&self, r2: Real) -> Real {
        -self.model.kernel.pair_factor(r2.sqrt(), self.eps_h2)
    }

    /// The weight `w_ij` of particle `i` with its fluid neighbour `j`; 0 for a
    /// neighbour at the same place, which the sums leave out.
    fn weight(&self, i: usize, j: usize) -> Real {
        let r2 = self.sep.between(self.pos[i], self.pos[j]).length_squared();
        if r2 > 0.0 {
            let inv_rho = 1.0 / self.rho[i];
            self.mass(i) * self.mass(j) * (self.mu[i] + self.mu[j]) * inv_rho / self.rho[j] * self.f(r2) * self.scale
        } else {
            0.0
        }
    }

    /// The no-slip walls' mirror weight `w_iw` of particle `i` (before the walls'
    /// shear factor).
    fn wall(&self, i: usize, n: usize, nb: &ChunkNeighbors) -> Real {
        let walls = &self.model.wall_particles;
        let psi = &walls.psi[self.material.map_or(0, |m| m[i] as usize)];
        let mut sum = 0.0;
        for &b in nb.walls(n) {
            let b = b as usize;
            let r2 = self.sep.between(self.pos[i], walls.positions[b]).length_squared();
            if r2 > 0.0 {
                sum += psi[b] * self.f(r2);
            }
        }
        let inv_rho = 1.0 / self.rho[i];
        self.mass(i) * 4.0 * self.mu[i] * inv_rho * inv_rho * sum * self.scale
    }
}

fn diagonal<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let (model, dt) = (cx.model, cx.dt);
    let shear = model.consts::<VaryingViscosity>().wall_shear;
    let (d_h, r_h) = (cx.attrs.handle::<Real>("visc_diag"), cx.attrs.handle::<Vec3>("visc_r"));
    let (mut diag, mut res) = (cx.attrs.take(d_h), cx.attrs.take(r_h));
    let attrs = &*cx.attrs;
    let pairs = Pairs::new(sep, model, attrs);
    let vel = attrs.get(attrs.handle::<Vec3>("v"));
    let chunks = diag.par_chunks_mut(CHUNK).zip(res.par_chunks_mut(CHUNK));
    chunks.zip(cx.nb.chunks.par_iter_mut()).enumerate().for_each(|(c, ((d_c, r_c), nb))| {
        // The products walk the same pairs 10 to 20 times a step: their weights are kept
        // beside the rows (the avalanche's product took 55 % of its step recomputed).
        nb.keep(|n, j| pairs.weight(c * CHUNK + n, j), |_, _| 0.0);
        for (n, (d_out, r_out)) in d_c.iter_mut().zip(r_c.iter_mut()).enumerate() {
            let i = c * CHUNK + n;
            let vi = vel[i];
            let (mut sum_w, mut force) = (0.0, Vec3::ZERO);
            for (&j, &w) in nb.fluid(n).iter().zip(nb.fluid_kept::<Real>(n)) {
                sum_w += w;
                force += (vel[j as usize] - vi) * w;
            }
            let w_wall = shear * pairs.wall(i, n, nb);
            *d_out = pairs.mass(i) + dt * (sum_w + w_wall);
            *r_out = (force - vi * w_wall) * dt;
        }
    });
    cx.attrs.put(d_h, diag);
    cx.attrs.put(r_h, res);
}

impl CpuPass for Precondition {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (p_h, dot_h, res_h) = (
            cx.attrs.handle::<Vec3>("visc_p"),
            cx.attrs.handle::<Real>("visc_dot"),
            cx.attrs.handle::<Real>("visc_residual"),
        );
        let (mut p, mut dot, mut r0z) = (cx.attrs.take(p_h), cx.attrs.take(dot_h), cx.attrs.take(res_h));
        let attrs = &*cx.attrs;
        let (r, d) = (attrs.get(attrs.handle::<Vec3>("visc_r")), attrs.get(attrs.handle::<Real>("visc_diag")));
        p.par_iter_mut().zip(dot.par_iter_mut()).zip(r0z.par_iter_mut()).enumerate().for_each(
            |(i, ((p, dot), r0z))| {
                let z = r[i] / d[i];
                *p = z;
                *dot = r[i].dot(z);
                *r0z = *dot;
            },
        );
        cx.attrs.put(p_h, p);
        cx.attrs.put(dot_h, dot);
        cx.attrs.put(res_h, r0z);
    }
}

/// `Ap` and `p.Ap` per particle, over the pair weights [`diagonal`] kept this step.
fn product(cx: &mut CpuCx<'_>) {
    let dt = cx.dt;
    let (ap_h, dot_h) = (cx.attrs.handle::<Vec3>("visc_ap"), cx.attrs.handle::<Real>("visc_dot"));
    let (mut ap, mut dot) = (cx.attrs.take(ap_h), cx.attrs.take(dot_h));
    let attrs = &*cx.attrs;
    let (p, d) = (attrs.get(attrs.handle::<Vec3>("visc_p")), attrs.get(attrs.handle::<Real>("visc_diag")));
    let chunks = ap.par_chunks_mut(CHUNK).zip(dot.par_chunks_mut(CHUNK));
    chunks.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((ap_c, dot_c), nb))| {
        for (n, (ap_out, dot_out)) in ap_c.iter_mut().zip(dot_c.iter_mut()).enumerate() {
            let i = c * CHUNK + n;
            let mut off = Vec3::ZERO;
            for (&j, &w) in nb.fluid(n).iter().zip(nb.fluid_kept::<Real>(n)) {
                off += p[j as usize] * w;
            }
            let out = p[i] * d[i] - off * dt;
            *ap_out = out;
            *dot_out = p[i].dot(out);
        }
    });
    cx.attrs.put(ap_h, ap);
    cx.attrs.put(dot_h, dot);
}

impl CpuPass for Update {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let s = cx.attrs.get(cx.attrs.handle::<Real>("visc_scalars")).to_vec();
        let (alpha, r0z) = (ratio(s[RZ as usize], s[PAP as usize]), s[R0Z as usize]);
        let (v_h, r_h) = (cx.attrs.handle::<Vec3>("v"), cx.attrs.handle::<Vec3>("visc_r"));
        let (dot_h, res_h) = (cx.attrs.handle::<Real>("visc_dot"), cx.attrs.handle::<Real>("visc_residual"));
        let (mut v, mut r) = (cx.attrs.take(v_h), cx.attrs.take(r_h));
        let (mut dot, mut res) = (cx.attrs.take(dot_h), cx.attrs.take(res_h));
        let attrs = &*cx.attrs;
        let (p, ap, d) = (
            attrs.get(attrs.handle::<Vec3>("visc_p")),
            attrs.get(attrs.handle::<Vec3>("visc_ap")),
            attrs.get(attrs.handle::<Real>("visc_diag")),
        );
        let outs = v.par_iter_mut().zip(r.par_iter_mut()).zip(dot.par_iter_mut()).zip(res.par_iter_mut());
        outs.enumerate().for_each(|(i, (((v, r), dot), res))| {
            *v += p[i] * alpha;
            *r -= ap[i] * alpha;
            let rz = r.dot(*r / d[i]);
            *dot = rz;
            *res = ratio(rz, r0z);
        });
        for (h, col) in [(v_h, v), (r_h, r)] {
            cx.attrs.put(h, col);
        }
        cx.attrs.put(dot_h, dot);
        cx.attrs.put(res_h, res);
    }
}

impl CpuPass for Direction {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let s = cx.attrs.get(cx.attrs.handle::<Real>("visc_scalars")).to_vec();
        let beta = ratio(s[RZ_NEW as usize], s[RZ as usize]);
        let p_h = cx.attrs.handle::<Vec3>("visc_p");
        let mut p = cx.attrs.take(p_h);
        let attrs = &*cx.attrs;
        let (r, d) = (attrs.get(attrs.handle::<Vec3>("visc_r")), attrs.get(attrs.handle::<Real>("visc_diag")));
        p.par_iter_mut().enumerate().for_each(|(i, p)| *p = r[i] / d[i] + *p * beta);
        cx.attrs.put(p_h, p);
    }
}
