//! Equations of state: pressure from density plus an optional background
//! pressure, clamped at zero so free surfaces never pull particles together (no
//! tensile instability).

use crate::materials::EquationOfState;
use crate::math::Real;

/// An equation of state with its constants resolved for one fluid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eos {
    /// The pressure law.
    pub law: Law,
    /// Background pressure (Pa) added before the clamp at zero.
    pub background: Real,
}

/// A pressure law p(rho) with its constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
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
            EquationOfState::Tait { gamma, background } => {
                Eos { law: Law::Tait { rho0, b: rho0 * c * c / gamma, gamma }, background }
            }
            EquationOfState::Linear { stiffness, background } => {
                Eos { law: Law::Linear { rho0, k: stiffness.unwrap_or(c * c) }, background }
            }
        }
    }

    /// Pressure (Pa) at density `rho` (kg/m^3): the law's plus the background,
    /// never negative.
    #[inline(always)]
    pub fn pressure(&self, rho: Real) -> Real {
        let p = match self.law {
            Law::Tait { rho0, b, gamma } => {
                let ratio = rho / rho0;
                // gamma = 7 is the common case: three multiplications instead of powf.
                let pow = if gamma == 7.0 {
                    let r2 = ratio * ratio;
                    r2 * r2 * r2 * ratio
                } else {
                    ratio.powf(gamma)
                };
                b * (pow - 1.0)
            }
            Law::Linear { rho0, k } => k * (rho - rho0),
        };
        (p + self.background).max(0.0)
    }

    /// The density (kg/m^3) at which the law (without the background) gives
    /// pressure `p` (Pa, >= 0): its inverse.
    pub fn density(&self, p: Real) -> Real {
        match self.law {
            Law::Tait { rho0, b, gamma } => rho0 * (1.0 + p / b).powf(1.0 / gamma),
            Law::Linear { rho0, k } => rho0 + p / k,
        }
    }

    /// The speed of sound (m/s) at rest density: `sqrt(dp/drho)`.
    pub fn sound_speed(&self) -> Real {
        match self.law {
            Law::Tait { rho0, b, gamma } => (b * gamma / rho0).sqrt(),
            Law::Linear { k, .. } => k.sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tait_matches_its_definition_and_clamps() {
        let eos = Eos::new(EquationOfState::Tait { gamma: 7.0, background: 0.0 }, 1000.0, 40.0);
        let b = 1000.0 * 1600.0 / 7.0;
        let expect = b * (1.01f32.powf(7.0) - 1.0);
        assert!((eos.pressure(1010.0) - expect).abs() < 1e-3 * expect);
        assert_eq!(eos.pressure(990.0), 0.0);
        assert!((eos.sound_speed() - 40.0).abs() < 1e-3);
        let lin = Eos::new(EquationOfState::Linear { stiffness: None, background: 0.0 }, 1000.0, 40.0);
        assert!((lin.pressure(1001.0) - 1600.0).abs() < 0.1);
        assert_eq!(lin.pressure(900.0), 0.0);
    }

    #[test]
    fn a_background_pressure_carries_tension_down_to_minus_itself() {
        let lin = Eos::new(EquationOfState::Linear { stiffness: None, background: 800.0 }, 1000.0, 40.0);
        assert!((lin.pressure(1000.0) - 800.0).abs() < 1e-3);
        assert!((lin.pressure(999.75) - 400.0).abs() < 0.1);
        assert_eq!(lin.pressure(999.0), 0.0);
        let tait = Eos::new(EquationOfState::Tait { gamma: 7.0, background: 50.0 }, 1000.0, 40.0);
        assert!((tait.pressure(1000.0) - 50.0).abs() < 1e-3);
    }
}
