//! The WCSPH scheme's passes on the CPU.

use super::WcsphConsts;
use crate::cpu::neighbors::{CHUNK, gather};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use rayon::prelude::*;

/// `pterm = p / rho^2` (m^5/(kg s^2)) from each particle's material's equation of state.
#[derive(Debug)]
pub struct EosPass;

impl CpuPass for EosPass {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let eos = &cx.model.consts::<WcsphConsts>().eos;
        let (rho, pt) = (cx.attrs.handle::<Real>("rho"), cx.attrs.handle::<Real>("pterm"));
        let mut pterm = cx.attrs.take(pt);
        let rho = cx.attrs.get(rho);
        let mat = cx.attrs.find::<u32>("material").map(|m| cx.attrs.get(m));
        pterm.par_iter_mut().zip(rho.par_iter()).enumerate().with_min_len(4096).for_each(|(i, (pt, &r))| {
            let e = &eos[mat.map_or(0, |m| m[i] as usize)];
            *pt = e.pressure(r) / (r * r);
        });
        cx.attrs.put(pt, pterm);
    }
}

/// Fills `wall_p` (Pa) with the pressure of each wall particle, extrapolated from the
/// fluid around it (Adami, Hu & Adams 2012, J. Comput. Phys. 231, eq. 27; static
/// walls, so no wall acceleration term):
/// `p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf`.
/// Wall particles with no fluid near them get 0.
#[derive(Debug)]
pub struct WallPressure;

impl CpuPass for WallPressure {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| wall_pressure(cx, s))
    }
}

fn wall_pressure<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let g = model.gravity;
    let walls = &model.wall_particles;
    let wp = cx.attrs.handle::<Real>("wall_p");
    let mut wall_p = cx.attrs.take(wp);
    let attrs = &*cx.attrs;
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let (rho, pterm) = (attrs.get(attrs.handle::<Real>("rho")), attrs.get(attrs.handle::<Real>("pterm")));
    let grid = &*cx.grid;
    wall_p.par_iter_mut().zip(walls.positions.par_iter()).with_min_len(CHUNK).for_each_init(
        Vec::new,
        |nb, (p_b, &xb)| {
            nb.clear();
            gather(sep, grid, pos, xb, h2, nb);
            let (mut sum_w, mut sum_p, mut sum_rx) = (0.0, 0.0, Vec3::ZERO);
            for &j in nb.iter() {
                let j = j as usize;
                let x_bj = sep.between(xb, pos[j]);
                let w = k.w_r2(x_bj.length_squared());
                sum_w += w;
                sum_p += pterm[j] * rho[j] * rho[j] * w;
                sum_rx += x_bj * (rho[j] * w);
            }
            *p_b = if sum_w > 0.0 { ((sum_p + g.dot(sum_rx)) / sum_w).max(0.0) } else { 0.0 };
        },
    );
    cx.attrs.put(wp, wall_p);
}
