//! Equations of state: pressure from density, clamped at zero so free surfaces
//! never pull particles together (no tensile instability).

use crate::math::Real;
use crate::scene::EquationOfState;

/// An equation of state with its constants resolved for one fluid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Eos {
    /// Tait: `p = b ((rho/rho0)^gamma - 1)`, `b = rho0 c^2 / gamma`
    /// (Monaghan 1994, eq. 3.4; Becker & Teschner 2007, eq. 7).
    Tait {
        /// Rest density (kg/m^3).
        rho0: Real,
        /// Pressure constant b (Pa).
        b: Real,
        /// Exponent gamma.
        gamma: Real,
    },
    /// `p = k (rho - rho0)` (Müller et al. 2003, eq. 12).
    Linear {
        /// Rest density (kg/m^3).
        rho0: Real,
        /// Stiffness k (m^2/s^2).
        k: Real,
    },
}

impl Eos {
    /// Resolves a scene's equation of state for rest density `rho0` and speed of sound `c`.
    pub fn new(spec: EquationOfState, rho0: Real, c: Real) -> Self {
        match spec {
            EquationOfState::Tait { gamma } => Eos::Tait { rho0, b: rho0 * c * c / gamma, gamma },
            EquationOfState::Linear { stiffness } => Eos::Linear { rho0, k: stiffness.unwrap_or(c * c) },
        }
    }

    /// Pressure (Pa) at density `rho` (kg/m^3), never negative.
    #[inline(always)]
    pub fn pressure(&self, rho: Real) -> Real {
        match *self {
            Eos::Tait { rho0, b, gamma } => {
                let ratio = rho / rho0;
                // gamma = 7 is the common case: three multiplications instead of powf.
                let pow = if gamma == 7.0 {
                    let r2 = ratio * ratio;
                    r2 * r2 * r2 * ratio
                } else {
                    ratio.powf(gamma)
                };
                (b * (pow - 1.0)).max(0.0)
            }
            Eos::Linear { rho0, k } => (k * (rho - rho0)).max(0.0),
        }
    }

    /// The speed of sound (m/s) at rest density: `sqrt(dp/drho)`.
    pub fn sound_speed(&self) -> Real {
        match *self {
            Eos::Tait { rho0, b, gamma } => (b * gamma / rho0).sqrt(),
            Eos::Linear { k, .. } => k.sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tait_matches_its_definition_and_clamps() {
        let eos = Eos::new(EquationOfState::Tait { gamma: 7.0 }, 1000.0, 40.0);
        let b = 1000.0 * 1600.0 / 7.0;
        let expect = b * (1.01f32.powf(7.0) - 1.0);
        assert!((eos.pressure(1010.0) - expect).abs() < 1e-3 * expect);
        assert_eq!(eos.pressure(990.0), 0.0);
        assert!((eos.sound_speed() - 40.0).abs() < 1e-3);
        let lin = Eos::new(EquationOfState::Linear { stiffness: None }, 1000.0, 40.0);
        assert!((lin.pressure(1001.0) - 1600.0).abs() < 0.1);
        assert_eq!(lin.pressure(900.0), 0.0);
    }
}
