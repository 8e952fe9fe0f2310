//! The transport-velocity formulation (Adami, Hu & Adams 2013, J. Comput. Phys.
//! 241; `solver.transport_velocity`): the acceleration a uniform background
//! pressure `p_b` gives each particle, eq. 13's
//! `a_b = -p_b / m_i sum_j (V_i^2 + V_j^2) grad W_ij` with `V = m / rho`, written
//! `-p_b sum_j (m_i / rho_i^2 + m_j (m_j / m_i) / rho_j^2) grad W_ij`, and walls as in
//! the pressure force, `-p_b sum_b psi_b (1/rho_i^2 + 1/rho0^2) grad W_ib`. The
//! core's drift moves particles with `v + dt/2 a_b` (eq. 14); their velocity never
//! takes it. The extra stress of eq. 10, `rho v (v~ - v)`, is left out: it is
//! second order in dt, and without it the Taylor-Green decay rate is within the
//! validation bound (docs/validation/taylor-green).

use super::WcsphConsts;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// `a_transport` from the background pressure.
pub static TRANSPORT: PassSpec = PassSpec {
    name: "wcsph.transport",
    module: "wcsph",
    stage: Stage::Force,
    reads: &["x", "rho"],
    writes: &["a_transport"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The pass on the CPU.
#[derive(Debug)]
pub struct Transport;

impl CpuPass for Transport {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| transport(cx, s))
    }
}

fn transport<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let walls = &model.wall_particles;
    let materials = &model.materials;
    let p_b = model.consts::<WcsphConsts>().transport.expect("the pass runs only with a background pressure");
    let t_h = cx.attrs.handle::<Vec3>("a_transport");
    let mut out = cx.attrs.take(t_h);
    let attrs = &*cx.attrs;
    let (pos, rho) = (attrs.get(attrs.handle::<Vec3>("x")), attrs.get(attrs.handle::<Real>("rho")));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    let inv2 = |r: Real| 1.0 / (r * r);
    out.par_chunks_mut(crate::cpu::neighbors::CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (out_c, nb))| {
        for (n, out) in out_c.iter_mut().enumerate() {
            let i = c * crate::cpu::neighbors::CHUNK + n;
            let (xi, ma) = (pos[i], material(i));
            let m_i = materials.get(ma).mass;
            let own = m_i * inv2(rho[i]);
            let mut sum = Vec3::ZERO;
            for &j in nb.fluid(n) {
                let j = j as usize;
                let x_ij = sep.between(xi, pos[j]);
                let r2 = x_ij.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let m_j = materials.get(material(j)).mass;
                sum += x_ij * (k.dw_dr(r) / r * (own + m_j * (m_j / m_i) * inv2(rho[j])));
            }
            let (psi, wall) = (&walls.psi[ma], inv2(rho[i]) + inv2(materials.get(ma).rest_density));
            for &b in nb.walls(n) {
                let b = b as usize;
                let x_ib = sep.between(xi, walls.positions[b]);
                let r2 = x_ib.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                sum += x_ib * (k.dw_dr(r) / r * (psi[b] * wall));
            }
            *out = sum * -p_b;
        }
    });
    cx.attrs.put(t_h, out);
}
