//! The per-particle passes of the heat module.
//!
//! - Buoyancy in the Boussinesq approximation (as in the SPH seed, and Cleary &
//!   Monaghan 1999 for the convection they model): density stays constant except in
//!   the body force, `g (1 - beta (T - T0))`. The fluid's force pass already adds
//!   `g`; this one adds `-beta_i (T_i - T0) g`.
//! - Integration: `T += dt dT/dt` after the kick that follows an evaluation
//!   (explicit Euler, stable under the diffusion limit `dt <= 0.1 rho c h^2 / k`),
//!   summed with Kahan's compensation (`temperature_carry`): increments far below
//!   the f32 spacing of the temperature add up instead of rounding away.

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

/// `T += dt dT/dt`, compensated.
pub static INTEGRATE: PassSpec = PassSpec {
    name: "heat.integrate",
    module: "heat",
    stage: Stage::Kick,
    reads: &["heat_rate"],
    writes: &[],
    accumulates: &["temperature", "temperature_carry"],
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
        let (t_h, c_h) = (cx.attrs.handle::<Real>("temperature"), cx.attrs.handle::<Real>("temperature_carry"));
        let (mut temp, mut carry) = (cx.attrs.take(t_h), cx.attrs.take(c_h));
        let rate = cx.attrs.get(cx.attrs.handle::<Real>("heat_rate"));
        let each = temp.par_iter_mut().zip(carry.par_iter_mut()).zip(rate.par_iter()).with_min_len(4096);
        each.for_each(|((t, c), &r)| (*t, *c) = compensated_add(*t, *c, dt * r));
        cx.attrs.put(t_h, temp);
        cx.attrs.put(c_h, carry);
    }
}

/// Kahan's compensated sum: `sum + increment`, with `carry` the rounding the sum
/// dropped so far (subtracted first), and the new carry (integrate.wgsl does the
/// same operations in the same order).
#[inline(always)]
pub fn compensated_add(sum: Real, carry: Real, increment: Real) -> (Real, Real) {
    let y = increment - carry;
    let next = sum + y;
    (next, (next - sum) - y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn increments_below_the_rounding_add_up() {
        // 1e-6 K a step at 300 K (f32 spacing 3e-5 K): a million steps make 1 K.
        let (mut plain, mut sum, mut carry) = (300.0f32, 300.0f32, 0.0f32);
        for _ in 0..1_000_000 {
            plain += 1e-6;
            (sum, carry) = compensated_add(sum, carry, 1e-6);
        }
        assert_eq!(plain, 300.0);
        assert!((sum - carry - 301.0).abs() < 1e-4, "{sum} - {carry}");
    }
}
