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

/// Fills `rho` (kg/m^3) and `pterm = p / rho^2` (m^5/(kg s^2)).
pub fn density(model: &Model, grid: &Grid, pos: &[Vec3], rho: &mut [Real], pterm: &mut [Real]) {
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let m = model.fluid.mass;
    let walls: &BoundaryParticles = &model.boundary;
    rho.par_iter_mut().zip(pterm.par_iter_mut()).enumerate().with_min_len(CHUNK).for_each(|(i, (rho_i, pt))| {
        let xi = pos[i];
        let mut sum = 0.0;
        grid.for_each_run(xi, |run| {
            for &xj in &pos[run] {
                let r2 = (xi - xj).length_squared();
                if r2 < h2 {
                    sum += k.w_r2(r2);
                }
            }
        });
        let mut wall = 0.0;
        walls.grid.for_each_run(xi, |run| {
            for (&xb, &psi) in walls.positions[run.clone()].iter().zip(&walls.psi[run]) {
                let r2 = (xi - xb).length_squared();
                if r2 < h2 {
                    wall += psi * k.w_r2(r2);
                }
            }
        });
        let r = m * sum + wall;
        *rho_i = r;
        *pt = model.fluid.eos.pressure(r) / (r * r);
    });
}

/// Fills `wall_p` (Pa) with the pressure of each wall particle, extrapolated from
/// the fluid around it (Adami et al. 2012, eq. 27; static walls, so no wall
/// acceleration term). Wall particles with no fluid near them get 0.
pub fn wall_pressure(model: &Model, grid: &Grid, pos: &[Vec3], rho: &[Real], pterm: &[Real], wall_p: &mut [Real]) {
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let g = model.gravity;
    let walls = &model.boundary;
    wall_p.par_iter_mut().zip(walls.positions.par_iter()).with_min_len(CHUNK).for_each(|(p_b, &xb)| {
        let (mut sum_w, mut sum_p, mut sum_rx) = (0.0, 0.0, Vec3::ZERO);
        grid.for_each_run(xb, |run| {
            for j in run {
                let x_bj = xb - pos[j];
                let r2 = x_bj.length_squared();
                if r2 < h2 {
                    let w = k.w_r2(r2);
                    sum_w += w;
                    sum_p += pterm[j] * rho[j] * rho[j] * w;
                    sum_rx += x_bj * (rho[j] * w);
                }
            }
        });
        *p_b = if sum_w > 0.0 { ((sum_p + g.dot(sum_rx)) / sum_w).max(0.0) } else { 0.0 };
    });
}

/// Fills `acc` (m/s^2) with gravity, pressure and viscous accelerations, and
/// `xsph` (m/s), the XSPH velocity correction, when the fluid uses it.
#[allow(clippy::too_many_arguments)]
pub fn forces(
    model: &Model,
    grid: &Grid,
    pos: &[Vec3],
    vel: &[Vec3],
    rho: &[Real],
    pterm: &[Real],
    wall_p: &[Real],
    acc: &mut [Vec3],
    xsph: Option<&mut [Vec3]>,
) {
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let f = &model.fluid;
    let m = f.mass;
    let walls = &model.boundary;
    let eps = f.xsph;
    let inv_rho0_2 = 1.0 / (f.rho0 * f.rho0);
    let one = |i: usize| -> (Vec3, Vec3) {
        let (xi, vi, rho_i, pt_i) = (pos[i], vel[i], rho[i], pterm[i]);
        let mut a = model.gravity;
        let mut dv = Vec3::ZERO;
        grid.for_each_run(xi, |run| {
            for j in run {
                let x_ij = xi - pos[j];
                let r2 = x_ij.length_squared();
                if r2 >= h2 || r2 == 0.0 {
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
        });
        walls.grid.for_each_run(xi, |run| {
            for ((&xb, &psi), &p_b) in
                walls.positions[run.clone()].iter().zip(&walls.psi[run.clone()]).zip(&wall_p[run])
            {
                let x_ib = xi - xb;
                let r2 = x_ib.length_squared();
                if r2 >= h2 || r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let grad = x_ib * (k.dw_dr(r) / r);
                a -= grad * (psi * (pt_i + p_b * inv_rho0_2));
                a += f.viscosity.pair(k, x_ib, r, vi, psi, rho_i, f.rho0, grad);
            }
        });
        (a, dv * eps)
    };
    match xsph {
        Some(xsph) => {
            acc.par_iter_mut().zip(xsph.par_iter_mut()).enumerate().with_min_len(CHUNK).for_each(|(i, (a, dv))| {
                (*a, *dv) = one(i);
            })
        }
        None => acc.par_iter_mut().enumerate().with_min_len(CHUNK).for_each(|(i, a)| *a = one(i).0),
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
