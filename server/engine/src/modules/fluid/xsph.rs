//! XSPH (Monaghan 1989, J. Comput. Phys. 82, eq. 2.6): each particle's velocity is
//! nudged towards its neighbours' average after the kick that follows an evaluation,
//! `dv_i = eps_i sum_j 2 m_j / (rho_i + rho_j) (v_j - v_i) W_ij`. Two passes: the sum
//! with the forces, and the nudge in the kick stage. Only scenes with XSPH run them.

use super::FluidConsts;
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// The XSPH sum.
pub static SUM: PassSpec = PassSpec {
    name: "fluid.xsph",
    module: "fluid",
    stage: Stage::Force,
    reads: &["x", "v", "rho"],
    writes: &["xsph"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The nudge, `v += dv`.
pub static KICK: PassSpec = PassSpec {
    name: "fluid.xsph_kick",
    module: "fluid",
    stage: Stage::Kick,
    reads: &["xsph"],
    writes: &[],
    accumulates: &["v"],
    tolerance: 1e-6,
};

/// The XSPH sum on the CPU, over the step's neighbour lists.
#[derive(Debug)]
pub struct Xsph;

impl CpuPass for Xsph {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| xsph(cx, s))
    }
}

fn xsph<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let fc: &FluidConsts = model.consts();
    let h = cx.attrs.handle::<Vec3>("xsph");
    let mut dv_all = cx.attrs.take(h);
    let attrs = &*cx.attrs;
    let (pos, vel, rho) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
    );
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    dv_all.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (dv_c, nb))| {
        for (n, out) in dv_c.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let (xi, vi, rho_i) = (pos[i], vel[i], rho[i]);
            let mut dv = Vec3::ZERO;
            for &j in nb.fluid(n) {
                let j = j as usize;
                let r2 = sep.between(xi, pos[j]).length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let m = model.materials.get(material(j)).mass;
                dv -= (vi - vel[j]) * (2.0 * m / (rho_i + rho[j]) * k.w_r2(r2));
            }
            *out = dv * fc.xsph[material(i)];
        }
    });
    cx.attrs.put(h, dv_all);
}

/// `v += dv` on the CPU.
#[derive(Debug)]
pub struct XsphKick;

impl CpuPass for XsphKick {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (v, x) = (cx.attrs.handle::<Vec3>("v"), cx.attrs.handle::<Vec3>("xsph"));
        let mut vel = cx.attrs.take(v);
        vel.par_iter_mut().zip(cx.attrs.get(x).par_iter()).with_min_len(4096).for_each(|(v, &dv)| *v += dv);
        cx.attrs.put(v, vel);
    }
}
