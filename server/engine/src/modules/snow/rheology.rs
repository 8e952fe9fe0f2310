//! The viscosity laws, resolved into one form both backends evaluate with the same
//! arithmetic (snow.wgsl's `viscosity_of`): a kind, four parameters and the clamp.
//!
//! The shear rate is `g = sqrt(2 D:D)`, which for a simple shear `u(y)` is `|du/dy|`,
//! so the laws' constants mean what rheometers report. Where a law is singular at
//! rest (a power law with n < 1, a yield stress) the clamp `max` bounds it; the
//! regularised yield term `tau_0 (1 - exp(-m g)) / g` tends to `tau_0 m` at rest
//! and is evaluated by its series `tau_0 m (1 - m g / 2)` where `m g < 1e-3` so the
//! subtraction does not cancel.

use super::spec::Rheology;
use crate::math::Real;

/// A law's kind, as the GPU uniform stores it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum Kind {
    /// No viscosity.
    None = 0,
    /// p = [mu].
    Newtonian = 1,
    /// p = [mu_0, mu_inf, K, n].
    Cross = 2,
    /// p = [K, n].
    PowerLaw = 3,
    /// p = [tau_0, mu_p, m].
    Bingham = 4,
    /// p = [tau_0, K, n, m].
    HerschelBulkley = 5,
    /// p = [mu_0, mu_inf, lambda, n].
    Carreau = 6,
}

/// A resolved law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// Which law.
    pub kind: Kind,
    /// Its parameters, in the order [`Kind`] lists.
    pub p: [Real; 4],
    /// The clamp (Pa s).
    pub max: Real,
}

impl Law {
    /// Resolves a scene's rheology with the scene's clamp `max` (Pa s).
    pub fn new(r: &Rheology, max: Real) -> Self {
        let (kind, p) = match *r {
            Rheology::None => (Kind::None, [0.0; 4]),
            Rheology::Newtonian { mu } => (Kind::Newtonian, [mu, 0.0, 0.0, 0.0]),
            Rheology::Cross { mu_0, mu_inf, k, n } => (Kind::Cross, [mu_0, mu_inf, k, n]),
            Rheology::PowerLaw { k, n } => (Kind::PowerLaw, [k, n, 0.0, 0.0]),
            Rheology::Bingham { yield_stress, mu_p, m } => (Kind::Bingham, [yield_stress, mu_p, m, 0.0]),
            Rheology::HerschelBulkley { yield_stress, k, n, m } => (Kind::HerschelBulkley, [yield_stress, k, n, m]),
            Rheology::Carreau { mu_0, mu_inf, lambda, n } => (Kind::Carreau, [mu_0, mu_inf, lambda, n]),
        };
        Law { kind, p, max: max.min(Self { kind, p, max }.bound()) }
    }

    /// The largest viscosity the law itself reaches (Pa s), infinite where it is
    /// unbounded.
    fn bound(&self) -> Real {
        let p = self.p;
        match self.kind {
            Kind::None => 0.0,
            Kind::Newtonian => p[0],
            Kind::Cross | Kind::Carreau => p[0].max(p[1]),
            Kind::Bingham => p[1] + p[0] * p[2],
            Kind::PowerLaw | Kind::HerschelBulkley => Real::INFINITY,
        }
    }

    /// Dynamic viscosity (Pa s) at shear rate `g` (1/s), clamped to `[0, max]`.
    #[inline(always)]
    pub fn viscosity(&self, g: Real) -> Real {
        let p = self.p;
        let mu = match self.kind {
            Kind::None => 0.0,
            Kind::Newtonian => p[0],
            Kind::Cross => p[1] + (p[0] - p[1]) / (1.0 + (p[2] * g).powf(p[3])),
            Kind::PowerLaw => p[0] * g.powf(p[1] - 1.0),
            Kind::Bingham => p[1] + yield_term(p[0], p[2], g),
            Kind::HerschelBulkley => p[1] * g.powf(p[2] - 1.0) + yield_term(p[0], p[3], g),
            Kind::Carreau => p[1] + (p[0] - p[1]) * (1.0 + (p[2] * g) * (p[2] * g)).powf(0.5 * (p[3] - 1.0)),
        };
        // NaN (0^negative is infinite, never NaN) cannot arise; min/max order keeps
        // an infinite power law at the clamp.
        mu.min(self.max).max(0.0)
    }
}

/// Papanastasiou's regularised yield term `tau_0 (1 - exp(-m g)) / g` (Pa s).
#[inline(always)]
fn yield_term(tau0: Real, m: Real, g: Real) -> Real {
    let x = m * g;
    if x < 1e-3 { tau0 * m * (1.0 - 0.5 * x) } else { tau0 * (1.0 - (-x).exp()) / g }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(r: Rheology) -> Law {
        Law::new(&r, 1e6)
    }

    #[test]
    fn cross_spans_its_plateaus() {
        let l = law(Rheology::Cross { mu_0: 100.0, mu_inf: 0.1, k: 1.0, n: 1.0 });
        assert!((l.viscosity(0.0) - 100.0).abs() < 1e-4);
        // At K g = 1 it is halfway.
        assert!((l.viscosity(1.0) - 50.05).abs() < 1e-3);
        assert!((l.viscosity(1e7) - 0.1).abs() < 1e-3);
    }

    #[test]
    fn power_law_is_singular_at_rest_and_clamped() {
        let l = Law::new(&Rheology::PowerLaw { k: 2.0, n: 0.5 }, 50.0);
        assert_eq!(l.viscosity(0.0), 50.0);
        assert!((l.viscosity(4.0) - 1.0).abs() < 1e-6);
        let thick = law(Rheology::PowerLaw { k: 2.0, n: 2.0 });
        assert_eq!(thick.viscosity(0.0), 0.0);
        assert!((thick.viscosity(3.0) - 6.0).abs() < 1e-5);
    }

    #[test]
    fn yield_stress_laws_tend_to_their_plastic_limit() {
        let b = law(Rheology::Bingham { yield_stress: 10.0, mu_p: 1.0, m: 100.0 });
        // At rest: mu_p + tau_0 m; the series and the exact form meet at m g = 1e-3.
        assert!((b.viscosity(0.0) - 1001.0).abs() < 1e-3);
        let (below, above) = (b.viscosity(0.99e-5), b.viscosity(1.01e-5));
        assert!((below - above).abs() < 1e-3 * below, "{below} {above}");
        // Sheared well past 1/m: stress tau_0 + mu_p g.
        let g = 50.0;
        assert!((b.viscosity(g) * g - (10.0 + g)).abs() < 1e-3);
        let hb = law(Rheology::HerschelBulkley { yield_stress: 10.0, k: 2.0, n: 0.5, m: 100.0 });
        assert!((hb.viscosity(g) * g - (10.0 + 2.0 * g.sqrt())).abs() < 1e-3);
    }

    #[test]
    fn carreau_and_the_clamp() {
        let c = law(Rheology::Carreau { mu_0: 10.0, mu_inf: 0.0, lambda: 1.0, n: 0.0 });
        // n = 0: mu_0 / sqrt(1 + g^2).
        assert!((c.viscosity(3.0) - 10.0 / 10f32.sqrt()).abs() < 1e-5);
        let clamped = Law::new(&Rheology::Cross { mu_0: 1e5, mu_inf: 1.0, k: 1.0, n: 1.0 }, 1e3);
        assert_eq!(clamped.max, 1e3);
        assert_eq!(clamped.viscosity(0.0), 1e3);
        assert_eq!(Law::new(&Rheology::Newtonian { mu: 2.0 }, 1e3).max, 2.0);
    }
}
