//! The viscous passes of a generalised Newtonian fluid, over the step's neighbour
//! lists (the GPU's shear.wgsl and viscosity.wgsl add the same terms in the same
//! order):
//!
//! 1. `snow.shear`: the SPH velocity gradient
//!    `L_i = 1/rho_i sum_j m_j (v_j - v_i) (x) grad_i W_ij` (Monaghan 2005, Rep. Prog.
//!    Phys. 68, eq. 2.12, the difference form, exact for a uniform flow), the strain
//!    rate `D = (L + L^T) / 2`, the shear rate `g = sqrt(2 D:D)` and the viscosity
//!    `mu_i = mu(g)` of the particle's law.
//! 2. `snow.viscosity`: the viscous force with each pair's viscosity `mu_i + mu_j`,
//!    `a_i = sum_j m_j (mu_i + mu_j) / (rho_i rho_j) F_ij v_ij`,
//!    `F_ij = x_ij . grad_i W_ij / (r_ij^2 + 0.01 h^2)` (Morris, Fox & Zhu 1997,
//!    J. Comput. Phys. 136, eq. 8, with the per-particle viscosity of their variable-
//!    viscosity form). It is the divergence of the stress `2 mu D` where the flow is
//!    incompressible and the viscosity varies across the flow only (channel and
//!    sheared layers); the pairwise difference couples every neighbour directly. The
//!    divergence of a per-particle stress tensor (a gradient of a gradient) was
//!    measured first: on the channel flows its stencil lets neighbouring layers
//!    decouple in pairs (an odd-even mode no term damps), with velocity errors of
//!    20 % to 120 %.
//!
//! Each pair's term is antisymmetric, so momentum is conserved, and
//! `sum_i m_i v_i . a_i = -1/2 sum_ij m_i m_j (mu_i + mu_j) / (rho_i rho_j) |F_ij| |v_ij|^2`:
//! the force only ever dissipates kinetic energy, whatever the viscosities. A wall
//! particle b (pseudo-mass `psi_b`) is the mirror image of the fluid particle it acts
//! on: velocity `-v_i`, viscosity `mu_i`, density `rho_i` (no slip on the wall surface,
//! half a spacing in front of the first wall layer, instead of at the wall particles).
//! With `snow.walls = "slip"` walls take no part in either pass (no shear from them).

use super::SnowConsts;
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// Shear rate and viscosity per particle.
pub static SHEAR: PassSpec = PassSpec {
    name: "snow.shear",
    module: "snow",
    stage: Stage::PreForce,
    reads: &["x", "v", "rho"],
    writes: &["mu", "shear_rate"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The viscous force, added to the accelerations.
pub static VISCOSITY: PassSpec = PassSpec {
    name: "snow.viscosity",
    module: "snow",
    stage: Stage::Force,
    reads: &["x", "v", "rho", "mu"],
    writes: &[],
    accumulates: &["a"],
    tolerance: 1e-4,
};

/// `snow.shear` on the CPU.
#[derive(Debug)]
pub struct Shear;

impl CpuPass for Shear {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| shear(cx, s))
    }
}

/// `snow.viscosity` on the CPU.
#[derive(Debug)]
pub struct Viscosity;

impl CpuPass for Viscosity {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| viscosity(cx, s))
    }
}

/// `xx, yy, zz, xy, xz, yz` of `(L + L^T) / 2`, L given by rows.
#[inline(always)]
pub fn strain_rate(l: [Vec3; 3]) -> [Real; 6] {
    [l[0].x, l[1].y, l[2].z, 0.5 * (l[0].y + l[1].x), 0.5 * (l[0].z + l[2].x), 0.5 * (l[1].z + l[2].y)]
}

/// `sqrt(2 D:D)` (1/s), off-diagonal components counted twice.
#[inline(always)]
pub fn shear_rate(d: &[Real; 6]) -> Real {
    let diag = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let off = d[3] * d[3] + d[4] * d[4] + d[5] * d[5];
    (2.0 * (diag + 2.0 * off)).sqrt()
}

fn shear<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let sc: &SnowConsts = model.consts();
    let materials = &model.materials;
    let walls = &model.wall_particles;
    let (mu_h, g_h) = (cx.attrs.handle::<Real>("mu"), cx.attrs.handle::<Real>("shear_rate"));
    let (mut mu, mut rate) = (cx.attrs.take(mu_h), cx.attrs.take(g_h));
    let attrs = &*cx.attrs;
    let (pos, vel, rho) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
    );
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    let chunks = mu.par_chunks_mut(CHUNK).zip(rate.par_chunks_mut(CHUNK));
    chunks.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((mu_c, rate_c), nb))| {
        for (n, (mu_out, rate_out)) in mu_c.iter_mut().zip(rate_c.iter_mut()).enumerate() {
            let i = c * CHUNK + n;
            let (xi, vi, ma) = (pos[i], vel[i], material(i));
            let inv_rho = 1.0 / rho[i];
            let mut l = [Vec3::ZERO; 3];
            for &j in nb.fluid(n) {
                let j = j as usize;
                let x_ij = sep.between(xi, pos[j]);
                let r2 = x_ij.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let grad = x_ij * (k.dw_dr(r) / r);
                let dv = (vel[j] - vi) * (materials.get(material(j)).mass * inv_rho);
                l[0] += grad * dv.x;
                l[1] += grad * dv.y;
                l[2] += grad * dv.z;
            }
            let psi = &walls.psi[ma];
            for &b in nb.walls(n) {
                let b = b as usize;
                let x_ib = sep.between(xi, walls.positions[b]);
                let r2 = x_ib.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let grad = x_ib * (k.dw_dr(r) / r);
                let dv = vi * (-2.0 * sc.wall_shear * psi[b] * inv_rho);
                l[0] += grad * dv.x;
                l[1] += grad * dv.y;
                l[2] += grad * dv.z;
            }
            let g = shear_rate(&strain_rate(l));
            *rate_out = g;
            *mu_out = sc.laws[ma].viscosity(g);
        }
    });
    cx.attrs.put(mu_h, mu);
    cx.attrs.put(g_h, rate);
}

fn viscosity<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let sc: &SnowConsts = model.consts();
    let materials = &model.materials;
    let walls = &model.wall_particles;
    let eps_h2 = 0.01 * 0.25 * k.support() * k.support();
    let a_h = cx.attrs.handle::<Vec3>("a");
    let mut acc = cx.attrs.take(a_h);
    let attrs = &*cx.attrs;
    let (pos, vel, rho, mu) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
        attrs.get(attrs.handle::<Real>("mu")),
    );
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    acc.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (acc_c, nb))| {
        for (n, out) in acc_c.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let (xi, vi, mu_i, ma) = (pos[i], vel[i], mu[i], material(i));
            let inv_rho = 1.0 / rho[i];
            let mut a = Vec3::ZERO;
            for &j in nb.fluid(n) {
                let j = j as usize;
                let x_ij = sep.between(xi, pos[j]);
                let r2 = x_ij.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let f = r * k.dw_dr(r) / (r2 + eps_h2);
                let m = materials.get(material(j)).mass;
                a += (vi - vel[j]) * (m * (mu_i + mu[j]) * inv_rho / rho[j] * f);
            }
            let psi = &walls.psi[ma];
            let mirror = vi * (4.0 * sc.wall_shear * mu_i * inv_rho * inv_rho);
            for &b in nb.walls(n) {
                let b = b as usize;
                let r2 = sep.between(xi, walls.positions[b]).length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                a += mirror * (psi[b] * (r * k.dw_dr(r) / (r2 + eps_h2)));
            }
            *out += a;
        }
    });
    cx.attrs.put(a_h, acc);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_shear_has_its_rate_as_shear_rate() {
        // u = (s y, 0, 0): L row x = (0, s, 0).
        let s = 3.0;
        let d = strain_rate([Vec3::new(0.0, s, 0.0), Vec3::ZERO, Vec3::ZERO]);
        assert_eq!(d, [0.0, 0.0, 0.0, 0.5 * s, 0.0, 0.0]);
        assert!((shear_rate(&d) - s).abs() < 1e-6);
        // A pure rotation has no shear.
        let d = strain_rate([Vec3::new(0.0, s, 0.0), Vec3::new(-s, 0.0, 0.0), Vec3::ZERO]);
        assert_eq!(shear_rate(&d), 0.0);
    }
}
