//! The force pass: gravity, viscosity and, under WCSPH, pressure, in one loop over
//! the step's neighbour lists (the order of the sums is part of the result: the
//! GPU's forces.wgsl adds the same terms in the same order).
//!
//! - Symmetric pressure acceleration (Monaghan 1992, eq. 3.3), for several materials
//!   in the number-density form of Solenthaler & Pajarola (2008, eq. 6):
//!   `a_i = -1/m_i sum_j (m_i^2 p_i/rho_i^2 + m_j^2 p_j/rho_j^2) grad W_ij`, written
//!   `-sum_j m_j (r_ij p_i/rho_i^2 + r_ji p_j/rho_j^2) grad W_ij` with `r_ij = m_i/m_j`,
//!   which for equal masses (`r = 1`) is the single-material form, bit for bit.
//! - Walls as particles with Akinci's pseudo-mass, given the pressure Adami, Hu &
//!   Adams (2012, eq. 27) extrapolate from the fluid (the WCSPH scheme's
//!   `wcsph.wall_pressure`): `- sum_b psi_b (p_i/rho_i^2 + p_b/rho0^2) grad W_ib`.
//!   Akinci's own wall term keeps only `p_i/rho_i^2`; measured on a resting column it
//!   needs twice the hydrostatic pressure next to every wall to hold the fluid up,
//!   and mirroring `p_b = p_i` instead pumped energy into the column until it blew up.
//! - Viscosity from [`super::viscosity`]; walls act as the mirror image of the
//!   particle under Laplacian viscosity and as particles at rest under artificial
//!   viscosity ([`super::viscosity::ViscosityModel::wall`]).

use super::FluidConsts;
use crate::cpu::neighbors::{CHUNK, ChunkNeighbors};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// Gravity and viscosity (schemes that solve pressure on their own).
pub static FORCES: PassSpec = PassSpec {
    name: "fluid.forces",
    module: "fluid",
    stage: Stage::Force,
    reads: &["x", "v", "rho"],
    writes: &["a"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// Gravity, viscosity and the WCSPH pressure force in one loop.
pub static WITH_PRESSURE: PassSpec = PassSpec {
    name: "fluid.forces",
    module: "fluid",
    stage: Stage::Force,
    reads: &["x", "v", "rho", "pterm", "wall_p"],
    writes: &["a"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The force pass on the CPU.
#[derive(Debug)]
pub struct Forces;

impl CpuPass for Forces {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| specialise(cx, s))
    }
}

fn specialise<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    match (cx.attrs.has("pterm"), cx.attrs.has("material")) {
        (false, false) => forces::<false, false, S>(cx, sep),
        (false, true) => forces::<false, true, S>(cx, sep),
        (true, false) => forces::<true, false, S>(cx, sep),
        (true, true) => forces::<true, true, S>(cx, sep),
    }
}

/// The loop, specialised on whether pressure is part of it, whether the scene has
/// several materials (one material reads no index and multiplies by no ratio) and
/// whether it is periodic.
fn forces<const PRESSURE: bool, const MULTI: bool, S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let walls = &model.wall_particles;
    let fc: &FluidConsts = model.consts();
    let materials = &model.materials;
    let count = materials.len();
    let a_h = cx.attrs.handle::<Vec3>("a");
    let mut acc = cx.attrs.take(a_h);
    let attrs = &*cx.attrs;
    let (pos, vel, rho) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
    );
    let (pterm, wall_p): (&[Real], &[Real]) = if PRESSURE {
        (attrs.get(attrs.handle::<Real>("pterm")), attrs.get(attrs.handle::<Real>("wall_p")))
    } else {
        (&[], &[])
    };
    let mat: &[u32] = if MULTI { attrs.get(attrs.handle::<u32>("material")) } else { &[] };
    let inv_rho0_2: Vec<Real> = materials.iter().map(|m| 1.0 / (m.rest_density * m.rest_density)).collect();
    let one = |nb: &ChunkNeighbors, n: usize, i: usize| -> Vec3 {
        let (xi, vi, rho_i) = (pos[i], vel[i], rho[i]);
        let pt_i = if PRESSURE { pterm[i] } else { 0.0 };
        let ma = if MULTI { mat[i] as usize } else { 0 };
        let mut a = model.gravity;
        for &j in nb.fluid(n) {
            let j = j as usize;
            let x_ij = sep.between(xi, pos[j]);
            let r2 = x_ij.length_squared();
            if r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let grad = x_ij * (k.dw_dr(r) / r);
            let mb = if MULTI { mat[j] as usize } else { 0 };
            let m = materials.get(mb).mass;
            if PRESSURE {
                if MULTI {
                    let (r_ab, r_ba) = (fc.mass_ratio[ma * count + mb], fc.mass_ratio[mb * count + ma]);
                    a -= grad * (m * (pt_i * r_ab + pterm[j] * r_ba));
                } else {
                    a -= grad * (m * (pt_i + pterm[j]));
                }
            }
            let v_ij = vi - vel[j];
            let visc = if MULTI { &fc.pair_viscosity[ma * count + mb] } else { &fc.viscosity[0] };
            a += visc.pair(k, x_ij, r, v_ij, m, rho_i, rho[j], grad);
        }
        let psi = &walls.psi[ma];
        let rho0 = materials.get(ma).rest_density;
        for &b in nb.walls(n) {
            let b = b as usize;
            let x_ib = sep.between(xi, walls.positions[b]);
            let r2 = x_ib.length_squared();
            if r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let grad = x_ib * (k.dw_dr(r) / r);
            let psi = psi[b];
            if PRESSURE {
                a -= grad * (psi * (pt_i + wall_p[b] * inv_rho0_2[ma]));
            }
            a += fc.viscosity[ma].wall(k, x_ib, r, vi, psi, rho_i, rho0, grad);
        }
        a
    };
    acc.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (acc_c, nb))| {
        for (n, a) in acc_c.iter_mut().enumerate() {
            *a = one(nb, n, c * CHUNK + n);
        }
    });
    cx.attrs.put(a_h, acc);
}
