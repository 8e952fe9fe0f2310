//! The shear-rate pass of a generalised Newtonian fluid, `snow.shear`, over the
//! step's neighbour lists (the GPU's shear.wgsl adds the same terms in the same
//! order): the SPH velocity gradient
//! `L_i = 1/rho_i sum_j m_j (v_j - v_i) (x) grad_i W_ij` (Monaghan 2005, Rep. Prog.
//! Phys. 68, eq. 2.12, the difference form, exact for a uniform flow), the strain
//! rate `D = (L + L^T) / 2`, the shear rate `g = sqrt(2 D:D)` and the viscosity
//! `mu_i = mu(g)` of the particle's law, into the core's per-particle viscosity,
//! whose force ([`crate::viscosity`]) follows.
//!
//! A wall particle b (pseudo-mass `psi_b`) is the mirror image of the fluid
//! particle, velocity `-v_i`, as in the force. With `snow.walls = "slip"` walls
//! take no part (no shear from them).

use super::SnowConsts;
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use crate::viscosity::VaryingViscosity;
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

/// The same, each viscosity scaled by the core's factor `viscosity_shift`, which
/// another module writes (the heat module's temperature shift; clamped to
/// `snow.max_viscosity` after scaling).
pub static SHEAR_SHIFTED: PassSpec = PassSpec {
    name: "snow.shear",
    module: "snow",
    stage: Stage::PreForce,
    reads: &["x", "v", "rho", "viscosity_shift"],
    writes: &["mu", "shear_rate"],
    accumulates: &[],
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
    let wall_shear = model.consts::<VaryingViscosity>().wall_shear;
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
    let shift = attrs.find::<Real>("viscosity_shift").map(|s| attrs.get(s));
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
                let dv = vi * (-2.0 * wall_shear * psi[b] * inv_rho);
                l[0] += grad * dv.x;
                l[1] += grad * dv.y;
                l[2] += grad * dv.z;
            }
            let g = shear_rate(&strain_rate(l));
            *rate_out = g;
            let law = &sc.laws[ma];
            *mu_out = match shift {
                Some(s) => (s[i] * law.viscosity(g)).min(law.max),
                None => law.viscosity(g),
            };
        }
    });
    cx.attrs.put(mu_h, mu);
    cx.attrs.put(g_h, rate);
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
