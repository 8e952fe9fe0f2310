//! The per-particle passes of the heat module.
//!
//! - Buoyancy in the Boussinesq approximation (as in the SPH seed, and Cleary &
//!   Monaghan 1999 for the convection they model): density stays constant except in
//!   the body force, `g (1 - beta (T - T0))`. The fluid's force pass already adds
//!   `g`; this one adds `-beta_i (T_i - T0) g`.
//! - Integration: `T += dt dT/dt` after the kick that follows an evaluation
//!   (explicit Euler, stable under the diffusion limit `dt <= 0.1 rho c h^2 / k`).

use super::HeatConsts;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// The Boussinesq term of the body force.
pub static BUOYANCY: PassSpec = PassSpec {
    name: "heat.buoyancy",
    module: "heat",
    stage: Stage::Force,
    reads: &["x", "temperature"],
    writes: &[],
    accumulates: &["a"],
    tolerance: 1e-5,
};

/// `T += dt dT/dt`.
pub static INTEGRATE: PassSpec = PassSpec {
    name: "heat.integrate",
    module: "heat",
    stage: Stage::Kick,
    reads: &["heat_rate"],
    writes: &[],
    accumulates: &["temperature"],
    tolerance: 1e-6,
};

/// Buoyancy on the CPU.
#[derive(Debug)]
pub struct Buoyancy;

impl CpuPass for Buoyancy {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let hc: &HeatConsts = cx.model.consts();
        let (g, t0) = (hc.gravity, hc.reference);
        let a_h = cx.attrs.handle::<Vec3>("a");
        let mut acc = cx.attrs.take(a_h);
        let temp = cx.attrs.get(cx.attrs.handle::<Real>("temperature"));
        let mat = cx.attrs.find::<u32>("material").map(|m| cx.attrs.get(m));
        acc.par_iter_mut().enumerate().with_min_len(4096).for_each(|(i, a)| {
            let beta = hc.expansion[mat.map_or(0, |m| m[i] as usize)];
            *a -= g * (beta * (temp[i] - t0));
        });
        cx.attrs.put(a_h, acc);
    }
}

/// The integration on the CPU.
#[derive(Debug)]
pub struct Integrate;

impl CpuPass for Integrate {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let (t_h, r_h) = (cx.attrs.handle::<Real>("temperature"), cx.attrs.handle::<Real>("heat_rate"));
        let mut temp = cx.attrs.take(t_h);
        let rate = cx.attrs.get(r_h);
        temp.par_iter_mut().zip(rate.par_iter()).with_min_len(4096).for_each(|(t, &r)| *t += dt * r);
        cx.attrs.put(t_h, temp);
    }
}
