//! The CPU backend's particle passes: density and pressure, then forces.
//!
//! WCSPH after Monaghan (1994, J. Comput. Phys. 110) and Becker & Teschner
//! (2007, "Weakly compressible SPH for free surface flows", SCA):
//! - density by summation, walls included (Akinci et al. 2012, eq. 6):
//!   `rho_i = m sum_j W_ij + sum_b psi_b W_ib`;
//! - symmetric pressure acceleration (Monaghan 1992, eq. 3.3), with wall particles
//!   weighted by Akinci's pseudo-mass and given the pressure that Adami, Hu &
//!   Adams (2012, J. Comput. Phys. 231, eq. 27) extrapolate from the fluid:
//!   `p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf`,
//!   `a_i = -m sum_j (p_i/rho_i^2 + p_j/rho_j^2) grad W_ij - sum_b psi_b (p_i/rho_i^2 + p_b/rho0^2) grad W_ib`.
//!   Akinci's own wall term keeps only `p_i/rho_i^2`; measured on a resting column
//!   it needs twice the hydrostatic pressure next to every wall to hold the fluid
//!   up, and mirroring `p_b = p_i` instead pumped energy into the column until it
//!   blew up. Adami's extrapolation balances the wall with the fluid's own gradient;
//! - viscosity from [`crate::viscosity`], walls acting as particles at rest;
//! - XSPH (Monaghan 1989, J. Comput. Phys. 82, eq. 2.6):
//!   `dv_i = eps sum_j 2 m / (rho_i + rho_j) (v_j - v_i) W_ij`.
//!
//! Every pass reads the arrays sorted by cell and writes one value per particle,
//! so particles run in parallel without locks.

use crate::boundary::BoundaryParticles;
use crate::guard::Measures;
use crate::math::{Aabb, Real, Vec3};
use crate::model::Model;
use crate::neighbors::Grid;
use rayon::prelude::*;

/// Particles per rayon task: large enough to amortise scheduling.
const CHUNK: usize = 512;

/// Appends to `out` the indices of the points of `pts` within the support of
/// `x` (squared distance below `h2`), from the grid's candidate runs.
///
/// The compaction is branch-free: every candidate is written and the cursor
/// advances only for a hit. About 15 % of candidates are hits, so a branch per
/// candidate would mispredict constantly; this is the hot loop of the step.
#[inline(always)]
fn gather(grid: &Grid, pts: &[Vec3], x: Vec3, h2: Real, out: &mut Vec<u32>) {
    grid.for_each_run(x, |run| {
        let mut n = out.len();
        out.resize(n + run.len(), 0);
        for (j, &p) in run.clone().zip(&pts[run]) {
            out[n] = j as u32;
            n += ((x - p).length_squared() < h2) as usize;
        }
        out.truncate(n);
    });
}

/// Neighbour lists (compressed rows) of one chunk of [`CHUNK`] consecutive
/// particles, found once per step by the density pass and reused by the force
/// pass. Chunks are independent, so they fill in parallel without a merge.
#[derive(Debug, Default)]
pub struct ChunkNeighbors {
    fluid_start: Vec<u32>,
    fluid: Vec<u32>,
    wall_start: Vec<u32>,
    walls: Vec<u32>,
}

impl ChunkNeighbors {
    fn clear(&mut self) {
        self.fluid_start.clear();
        self.fluid_start.push(0);
        self.fluid.clear();
        self.wall_start.clear();
        self.wall_start.push(0);
        self.walls.clear();
    }

    /// Fluid neighbours (self included) of the chunk's `k`-th particle.
    fn fluid(&self, k: usize) -> &[u32] {
        &self.fluid[self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize]
    }

    /// Wall neighbours of the chunk's `k`-th particle.
    fn walls(&self, k: usize) -> &[u32] {
        &self.walls[self.wall_start[k] as usize..self.wall_start[k + 1] as usize]
    }
}

/// Finds every particle's neighbours into `lists` and fills `rho` (kg/m^3) and
/// `pterm = p / rho^2` (m^5/(kg s^2)).
pub fn density(
    model: &Model,
    grid: &Grid,
    pos: &[Vec3],
    lists: &mut Vec<ChunkNeighbors>,
    rho: &mut [Real],
    pterm: &mut [Real],
) {
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let m = model.fluid.mass;
    let walls: &BoundaryParticles = &model.boundary;
    lists.resize_with(pos.len().div_ceil(CHUNK), Default::default);
    rho.par_chunks_mut(CHUNK).zip(pterm.par_chunks_mut(CHUNK)).zip(lists.par_iter_mut()).enumerate().for_each(
        |(c, ((rho_c, pt_c), nb))| {
            nb.clear();
            for (n, (rho_i, pt)) in rho_c.iter_mut().zip(pt_c.iter_mut()).enumerate() {
                let xi = pos[c * CHUNK + n];
                gather(grid, pos, xi, h2, &mut nb.fluid);
                nb.fluid_start.push(nb.fluid.len() as u32);
                gather(&walls.grid, &walls.positions, xi, h2, &mut nb.walls);
                nb.wall_start.push(nb.walls.len() as u32);
                let sum: Real = nb.fluid(n).iter().map(|&j| k.w_r2((xi - pos[j as usize]).length_squared())).sum();
                let wall: Real = nb
                    .walls(n)
                    .iter()
                    .map(|&b| walls.psi[b as usize] * k.w_r2((xi - walls.positions[b as usize]).length_squared()))
                    .sum();
                let r = m * sum + wall;
                *rho_i = r;
                *pt = model.fluid.eos.pressure(r) / (r * r);
            }
        },
    );
}

/// Fills `wall_p` (Pa) with the pressure of each wall particle, extrapolated from
/// the fluid around it (Adami et al. 2012, eq. 27; static walls, so no wall
/// acceleration term). Wall particles with no fluid near them get 0.
pub fn wall_pressure(model: &Model, grid: &Grid, pos: &[Vec3], rho: &[Real], pterm: &[Real], wall_p: &mut [Real]) {
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let g = model.gravity;
    let walls = &model.boundary;
    wall_p.par_iter_mut().zip(walls.positions.par_iter()).with_min_len(CHUNK).for_each_init(
        Vec::new,
        |nb, (p_b, &xb)| {
            nb.clear();
            gather(grid, pos, xb, h2, nb);
            let (mut sum_w, mut sum_p, mut sum_rx) = (0.0, 0.0, Vec3::ZERO);
            for &j in nb.iter() {
                let j = j as usize;
                let x_bj = xb - pos[j];
                let w = k.w_r2(x_bj.length_squared());
                sum_w += w;
                sum_p += pterm[j] * rho[j] * rho[j] * w;
                sum_rx += x_bj * (rho[j] * w);
            }
            *p_b = if sum_w > 0.0 { ((sum_p + g.dot(sum_rx)) / sum_w).max(0.0) } else { 0.0 };
        },
    );
}

/// Fills `acc` (m/s^2) with gravity, pressure and viscous accelerations, and
/// `xsph` (m/s), the XSPH velocity correction, when the fluid uses it. Uses the
/// neighbour lists the density pass found.
#[allow(clippy::too_many_arguments)]
pub fn forces(
    model: &Model,
    lists: &[ChunkNeighbors],
    pos: &[Vec3],
    vel: &[Vec3],
    rho: &[Real],
    pterm: &[Real],
    wall_p: &[Real],
    acc: &mut [Vec3],
    xsph: Option<&mut [Vec3]>,
) {
    let k = &model.kernel;
    let f = &model.fluid;
    let m = f.mass;
    let walls = &model.boundary;
    let eps = f.xsph;
    let inv_rho0_2 = 1.0 / (f.rho0 * f.rho0);
    let one = |nb: &ChunkNeighbors, n: usize, i: usize| -> (Vec3, Vec3) {
        let (xi, vi, rho_i, pt_i) = (pos[i], vel[i], rho[i], pterm[i]);
        let mut a = model.gravity;
        let mut dv = Vec3::ZERO;
        for &j in nb.fluid(n) {
            let j = j as usize;
            let x_ij = xi - pos[j];
            let r2 = x_ij.length_squared();
            if r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let grad = x_ij * (k.dw_dr(r) / r);
            a -= grad * (m * (pt_i + pterm[j]));
            let v_ij = vi - vel[j];
            a += f.viscosity.pair(k, x_ij, r, v_ij, m, rho_i, rho[j], grad);
            if eps > 0.0 {
                dv -= v_ij * (2.0 * m / (rho_i + rho[j]) * k.w_r2(r2));
            }
        }
        for &b in nb.walls(n) {
            let b = b as usize;
            let x_ib = xi - walls.positions[b];
            let r2 = x_ib.length_squared();
            if r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let grad = x_ib * (k.dw_dr(r) / r);
            let psi = walls.psi[b];
            a -= grad * (psi * (pt_i + wall_p[b] * inv_rho0_2));
            a += f.viscosity.pair(k, x_ib, r, vi, psi, rho_i, f.rho0, grad);
        }
        (a, dv * eps)
    };
    match xsph {
        Some(xsph) => acc.par_chunks_mut(CHUNK).zip(xsph.par_chunks_mut(CHUNK)).zip(lists).enumerate().for_each(
            |(c, ((acc_c, dv_c), nb))| {
                for (n, (a, dv)) in acc_c.iter_mut().zip(dv_c).enumerate() {
                    (*a, *dv) = one(nb, n, c * CHUNK + n);
                }
            },
        ),
        None => acc.par_chunks_mut(CHUNK).zip(lists).enumerate().for_each(|(c, (acc_c, nb))| {
            for (n, a) in acc_c.iter_mut().enumerate() {
                *a = one(nb, n, c * CHUNK + n).0;
            }
        }),
    }
}

/// Reduces the state to what the guard and the time step control need.
pub fn measure(pos: &[Vec3], vel: &[Vec3], acc: &[Vec3], rho: &[Real], rho0: Real, domain: Aabb) -> Measures {
    (0..pos.len())
        .into_par_iter()
        .with_min_len(4 * CHUNK)
        .fold(Measures::default, |mut m, i| {
            let (x, v, a) = (pos[i], vel[i], acc[i]);
            let i32_ = i as u32;
            if !(x.is_finite() && v.is_finite() && a.is_finite() && rho[i].is_finite()) {
                m.non_finite.get_or_insert(i32_);
                return m;
            }
            let s2 = v.length_squared();
            if s2 > m.max_speed2.0 {
                m.max_speed2 = (s2, i32_);
            }
            m.max_accel2 = m.max_accel2.max(a.length_squared());
            let c = (rho[i] - rho0) / rho0;
            if c > m.max_compression.0 {
                m.max_compression = (c, i32_);
            }
            m.sum_compression += c.max(0.0) as f64;
            if !domain.contains(x) {
                m.outside.get_or_insert(i32_);
            }
            m
        })
        .reduce(Measures::default, Measures::merge)
}
