//! Temperature-dependent viscosity: each fluid's law (`heat.fluids[*].viscosity`),
//! resolved into one form both backends evaluate with the same arithmetic (the
//! GPU's viscosity.wgsl), and the pass `heat.viscosity` that writes the core's
//! per-particle viscosity `mu` from the temperature before the forces. The force
//! of those viscosities is the core's ([`crate::viscosity`]).
//!
//! Where another module sets the viscosity from the fluid's state (the snow
//! module's rheology), a law scales it instead (a shift factor, as in
//! time-temperature superposition's vertical shift): `heat.viscosity_shift` writes
//! `a_T = mu(T) / mu(T0)` into the core's factor, T0 the module's reference
//! temperature, and the setter's viscosity is `a_T mu(shear rate)`, so the
//! rheology holds at T0 and stiffens or thins with the law around it
//! ([`crate::quantities`] decides which, from the modules' claims).

use super::HeatConsts;
use super::spec::ViscosityLaw;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::Real;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// Most points of a viscosity table (the GPU uniform's room).
pub const MAX_POINTS: usize = 8;

/// A law's kind, as the GPU uniform stores it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum Kind {
    /// No law: the fluid keeps its own viscosity model (`mu` = 0).
    None = 0,
    /// p = [mu_ref, T_ref, b].
    Exponential = 1,
    /// p = [mu_ref, 1 / T_ref, E/R].
    Arrhenius = 2,
    /// The table's points.
    Table = 3,
}

/// A resolved law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemperatureLaw {
    /// Which law.
    pub kind: Kind,
    /// Its parameters, in the order [`Kind`] lists.
    pub p: [Real; 3],
    /// A table's points `[T (K), mu (Pa s)]`, `points` of them.
    pub table: [[Real; 2]; MAX_POINTS],
    /// How many of `table` are used.
    pub points: usize,
    /// The clamp (Pa s).
    pub max: Real,
    /// `1 / mu(T0)` (1/(Pa s)) at the module's reference temperature T0, for the
    /// shift factor; 0 without a law.
    pub inv_reference: Real,
}

impl TemperatureLaw {
    /// Resolves a fluid's law (none: `None`) with the scene's clamp `max` (Pa s) and
    /// the reference temperature `t0` (K) of its shift factor.
    pub fn new(law: Option<&ViscosityLaw>, max: Real, t0: Real) -> Self {
        let mut r = TemperatureLaw {
            kind: Kind::None,
            p: [0.0; 3],
            table: [[0.0; 2]; MAX_POINTS],
            points: 0,
            max,
            inv_reference: 0.0,
        };
        match law {
            None => {}
            Some(&ViscosityLaw::Exponential { mu_ref, t_ref, b }) => {
                (r.kind, r.p) = (Kind::Exponential, [mu_ref, t_ref, b])
            }
            Some(&ViscosityLaw::Arrhenius { mu_ref, t_ref, activation_temperature }) => {
                (r.kind, r.p) = (Kind::Arrhenius, [mu_ref, 1.0 / t_ref, activation_temperature])
            }
            Some(ViscosityLaw::Table { points }) => {
                r.kind = Kind::Table;
                r.points = points.len().min(MAX_POINTS);
                r.table[..r.points].copy_from_slice(&points[..r.points]);
            }
        }
        let at_t0 = r.viscosity(t0);
        r.inv_reference = if at_t0 > 0.0 { 1.0 / at_t0 } else { 0.0 };
        r
    }

    /// The shift factor `mu(t) / mu(T0)` (dimensionless) a law gives a rheology at
    /// temperature `t` (K): 1 without a law (the rheology as it is).
    #[inline(always)]
    pub fn shift(&self, t: Real) -> Real {
        if self.kind == Kind::None { 1.0 } else { self.viscosity(t) * self.inv_reference }
    }

    /// Dynamic viscosity (Pa s) at temperature `t` (K), clamped to `[0, max]`.
    #[inline(always)]
    pub fn viscosity(&self, t: Real) -> Real {
        let p = self.p;
        let mu = match self.kind {
            Kind::None => return 0.0,
            Kind::Exponential => p[0] * (-p[2] * (t - p[1])).exp(),
            Kind::Arrhenius => p[0] * (p[2] * (1.0 / t - p[1])).exp(),
            Kind::Table => self.interpolate(t),
        };
        mu.min(self.max).max(0.0)
    }

    /// The table at `t`: linear between points, constant beyond the ends.
    #[inline(always)]
    fn interpolate(&self, t: Real) -> Real {
        let pts = &self.table[..self.points];
        if t <= pts[0][0] {
            return pts[0][1];
        }
        for w in pts.windows(2) {
            let ([t0, m0], [t1, m1]) = (w[0], w[1]);
            if t <= t1 {
                return m0 + (m1 - m0) * ((t - t0) / (t1 - t0));
            }
        }
        pts[self.points - 1][1]
    }

    /// The largest viscosity (Pa s) between temperatures `lo` and `hi` (K), for the
    /// explicit viscous limit: each law is monotonic between table points, so its
    /// ends and its points bound it.
    pub fn largest(&self, lo: Real, hi: Real) -> Real {
        let inside = self.table[..self.points].iter().map(|p| p[0]).filter(|t| (lo..=hi).contains(t));
        inside.chain([lo, hi]).map(|t| self.viscosity(t)).fold(0.0, Real::max)
    }
}

/// The viscosity of each particle from its temperature.
pub static VISCOSITY: PassSpec = PassSpec {
    name: "heat.viscosity",
    module: "heat",
    stage: Stage::PreForce,
    reads: &["x", "temperature"],
    writes: &["mu"],
    accumulates: &[],
    tolerance: 1e-5,
};

/// Each particle's shift factor of its fluid's rheology from its temperature (scenes
/// with the snow module).
pub static SHIFT: PassSpec = PassSpec {
    name: "heat.viscosity_shift",
    module: "heat",
    stage: Stage::PreForce,
    reads: &["x", "temperature"],
    writes: &["viscosity_shift"],
    accumulates: &[],
    tolerance: 1e-5,
};

/// `heat.viscosity` on the CPU.
#[derive(Debug)]
pub struct Viscosity;

impl CpuPass for Viscosity {
    fn run(&self, cx: &mut CpuCx<'_>) {
        per_particle(cx, "mu", TemperatureLaw::viscosity);
    }
}

/// `heat.viscosity_shift` on the CPU.
#[derive(Debug)]
pub struct Shift;

impl CpuPass for Shift {
    fn run(&self, cx: &mut CpuCx<'_>) {
        per_particle(cx, "viscosity_shift", TemperatureLaw::shift);
    }
}

/// Writes `out` of each particle from its material's law at its temperature.
fn per_particle(cx: &mut CpuCx<'_>, out: &str, f: fn(&TemperatureLaw, Real) -> Real) {
    let hc: &HeatConsts = cx.model.consts();
    let out_h = cx.attrs.handle::<Real>(out);
    let mut values = cx.attrs.take(out_h);
    let temp = cx.attrs.get(cx.attrs.handle::<Real>("temperature"));
    let mat = cx.attrs.find::<u32>("material").map(|m| cx.attrs.get(m));
    values.par_iter_mut().enumerate().with_min_len(4096).for_each(|(i, v)| {
        *v = f(&hc.viscosity[mat.map_or(0, |m| m[i] as usize)], temp[i]);
    });
    cx.attrs.put(out_h, values);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(l: ViscosityLaw) -> TemperatureLaw {
        TemperatureLaw::new(Some(&l), 1e6, 300.0)
    }

    #[test]
    fn the_exponential_and_arrhenius_laws_meet_their_reference() {
        let e = law(ViscosityLaw::Exponential { mu_ref: 2.0, t_ref: 300.0, b: 0.05 });
        assert!((e.viscosity(300.0) - 2.0).abs() < 1e-6);
        assert!((e.viscosity(320.0) - 2.0 * (-1.0f32).exp()).abs() < 1e-6);
        // Water: 1.0e-3 Pa s at 20 °C, E/R = 1900 K gives 0.33e-3 at 80 °C
        // (measured: 0.355e-3; one activation temperature fits water to about 7 %).
        let a = law(ViscosityLaw::Arrhenius { mu_ref: 1.0e-3, t_ref: 293.15, activation_temperature: 1900.0 });
        assert!((a.viscosity(293.15) - 1.0e-3).abs() < 1e-8);
        let hot = a.viscosity(353.15);
        assert!((hot - 0.332e-3).abs() < 0.01e-3, "{hot}");
    }

    #[test]
    fn a_table_is_linear_between_points_and_flat_beyond() {
        let t = law(ViscosityLaw::Table { points: vec![[280.0, 4.0], [300.0, 2.0], [340.0, 1.0]] });
        assert_eq!(t.viscosity(200.0), 4.0);
        assert!((t.viscosity(290.0) - 3.0).abs() < 1e-6);
        assert!((t.viscosity(320.0) - 1.5).abs() < 1e-6);
        assert_eq!(t.viscosity(400.0), 1.0);
        assert_eq!(t.largest(290.0, 400.0), 3.0);
    }

    #[test]
    fn the_clamp_bounds_a_law_far_below_its_reference() {
        let a = TemperatureLaw::new(
            Some(&ViscosityLaw::Arrhenius { mu_ref: 1.0e-3, t_ref: 293.15, activation_temperature: 1900.0 }),
            10.0,
            293.15,
        );
        assert_eq!(a.viscosity(1.0), 10.0);
        assert_eq!(a.largest(1.0, 1e4), 10.0);
        assert_eq!(TemperatureLaw::new(None, 10.0, 300.0).viscosity(300.0), 0.0);
    }

    #[test]
    fn a_shift_is_the_law_over_its_value_at_the_reference_temperature() {
        let e = law(ViscosityLaw::Exponential { mu_ref: 2.0, t_ref: 280.0, b: 0.05 });
        assert!((e.shift(300.0) - 1.0).abs() < 1e-6);
        assert!((e.shift(320.0) - (-1.0f32).exp()).abs() < 1e-6);
        let t = law(ViscosityLaw::Table { points: vec![[280.0, 4.0], [300.0, 2.0], [340.0, 1.0]] });
        assert!((t.shift(290.0) - 1.5).abs() < 1e-6);
        assert_eq!(TemperatureLaw::new(None, 10.0, 300.0).shift(250.0), 1.0);
    }
}
