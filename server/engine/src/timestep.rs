//! Time step control.
//!
//! The stable limit is the smallest of (Monaghan 1992, section 10; Morris, Fox &
//! Zhu 1997, eqs. 19-20; with h the smoothing length, half the kernel support):
//! - CFL: `lambda h / (c + v_max)`, c the scheme's signal speed (WCSPH: the speed
//!   of sound);
//! - pressure: `lambda h / c_p`, `c_p = sqrt(p / rho)` the largest, where the
//!   pressure is a constraint's multiplier (DFSPH): the pressure force on a particle
//!   moved at fixed pressure (the constraint's geometric stiffness, Tournier et al.
//!   2015, "Stable constrained dynamics", ACM TOG 34(4), section 3) is of the order
//!   of `c_p^2 / h^2` per unit displacement and is integrated explicitly. A resting
//!   column on DFSPH grows a disorder from its floor above 0.6 to 0.7 `h / c_p`
//!   (docs/validation/schemes/CG.md);
//! - the modules' own limits (the fluid's viscous `0.125 h^2 / nu`, a heat
//!   module's diffusion limit, ...);
//! - force: `0.25 sqrt(h / |a|_max)`.
//!
//! Adaptive mode steps at that limit clamped to `[min, max]`; a limit below
//! `min` halts the scene (the run would otherwise crawl or blow up). Fixed mode
//! advances in intervals of `dt` and sub-steps an interval at the limit when
//! `dt` is larger, rather than stepping unstably.

use crate::math::Real;
use crate::scene::TimeStep;

/// Inputs of the stable limit, measured on the current state.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Smoothing length (m): half the kernel support radius.
    pub h: Real,
    /// Signal speed of the CFL condition (m/s): the speed of sound for WCSPH.
    pub c: Real,
    /// Largest particle speed (m/s).
    pub v_max: Real,
    /// The pressure's signal speed `sqrt(p / rho)` (m/s) of a scheme whose pressure
    /// is a constraint's multiplier (DFSPH), else 0.
    pub c_p: Real,
    /// Largest acceleration (m/s^2).
    pub a_max: Real,
    /// The smallest of the modules' limits (s) and its name, if any module limits dt.
    pub module: Option<(&'static str, Real)>,
}

impl Limits {
    /// The stable limit (s) for CFL number `cfl`.
    pub fn stable_dt(&self, cfl: Real) -> Real {
        self.binding(cfl).1
    }

    /// The limit that binds and its value (s): `cfl`, `pressure`, a module's limit, or
    /// `force`.
    pub fn binding(&self, cfl: Real) -> (&'static str, Real) {
        let mut dt = ("cfl", cfl * self.h / (self.c + self.v_max));
        if self.c_p > 0.0 && cfl * self.h / self.c_p < dt.1 {
            dt = ("pressure", cfl * self.h / self.c_p);
        }
        if let Some((name, limit)) = self.module
            && limit < dt.1
        {
            dt = (name, limit);
        }
        if self.a_max > 0.0 {
            let force = 0.25 * (self.h / self.a_max).sqrt();
            if force < dt.1 {
                dt = ("force", force);
            }
        }
        dt
    }
}

/// Chooses each step's dt and remembers where a fixed interval stands.
#[derive(Debug, Clone)]
pub struct StepControl {
    mode: TimeStep,
    /// Time left in the current fixed interval (s); 0 when a new one starts.
    remaining: Real,
    /// Steps taken beyond one per fixed interval.
    pub substeps: u64,
}

impl StepControl {
    /// The time-step settings.
    pub fn mode(&self) -> &TimeStep {
        &self.mode
    }

    /// Time left in the current fixed interval (s), for snapshots.
    pub fn remaining(&self) -> Real {
        self.remaining
    }

    /// Restores the state a snapshot recorded.
    pub fn restore(&mut self, remaining: Real, substeps: u64) {
        self.remaining = remaining;
        self.substeps = substeps;
    }

    /// Control for a scene's time-step settings.
    pub fn new(mode: TimeStep) -> Self {
        Self { mode, remaining: 0.0, substeps: 0 }
    }

    /// The next step's dt, or the reason the scene must halt.
    pub fn next_dt(&mut self, limits: &Limits) -> Result<Real, String> {
        match self.mode {
            TimeStep::Adaptive { cfl, min, max } => {
                let (binding, stable) = limits.binding(cfl);
                if stable.is_nan() || stable < min {
                    return Err(format!(
                        "stable time step {stable:.3e} s ({binding} limit) fell below solver.time_step.min = {min:.3e} s \
                         (max speed {:.3} m/s, max acceleration {:.3e} m/s^2)",
                        limits.v_max, limits.a_max
                    ));
                }
                Ok(stable.min(max))
            }
            TimeStep::Fixed { dt, cfl } => {
                if self.remaining <= 0.0 {
                    self.remaining = dt;
                } else {
                    self.substeps += 1;
                }
                let stable = limits.stable_dt(cfl);
                if stable.is_nan() || stable <= dt * 1e-4 {
                    return Err(format!(
                        "fixed step {dt:.3e} s would need more than 10000 sub-steps (stable limit {stable:.3e} s, \
                         max speed {:.3} m/s, max acceleration {:.3e} m/s^2)",
                        limits.v_max, limits.a_max
                    ));
                }
                // Equal sub-steps for what is left of the interval, none above the limit
                // (the limit read as 1e-5 larger, so that rounding in `remaining` does
                // not ask for one more): a short remainder after full steps would make
                // dt jump by a large factor and back, which the schemes' assumption of
                // a slowly varying dt does not survive (DFSPH's warm start gained 44 %
                // mechanical energy on the dam break under a fixed 10 ms interval).
                let parts = (self.remaining / (stable * (1.0 + 1e-5))).ceil().max(1.0);
                let step = self.remaining / parts;
                self.remaining -= step;
                // Do not leave a sliver of an interval for a separate tiny step.
                if self.remaining < 1e-6 * dt {
                    self.remaining = 0.0;
                }
                Ok(step)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(v_max: Real) -> Limits {
        Limits {
            h: 0.02,
            c: 40.0,
            v_max,
            c_p: 0.0,
            a_max: 10.0,
            module: Some(("viscosity", 0.125 * 0.02 * 0.02 / 1e-6)),
        }
    }

    #[test]
    fn stable_dt_takes_the_smallest_limit() {
        let l = limits(0.0);
        assert!((l.stable_dt(0.25) - 0.25 * 0.02 / 40.0).abs() < 1e-9);
        let viscous = Limits { module: Some(("viscosity", 0.125 * 0.02 * 0.02)), ..l };
        assert!((viscous.stable_dt(0.25) - 0.125 * 0.02 * 0.02).abs() < 1e-9);
        assert_eq!(viscous.binding(0.25).0, "viscosity");
        let forced = Limits { a_max: 1e6, ..l };
        assert!((forced.stable_dt(0.25) - 0.25 * (0.02f32 / 1e6).sqrt()).abs() < 1e-9);
        // The pressure's speed binds alone, not added to the flow's.
        let constrained = Limits { c: 0.0, v_max: 2.0, c_p: 4.0, a_max: 0.0, module: None, ..l };
        assert_eq!(constrained.binding(0.5), ("pressure", 0.5 * 0.02 / 4.0));
        assert_eq!(Limits { v_max: 8.0, ..constrained }.binding(0.5), ("cfl", 0.5 * 0.02 / 8.0));
    }

    #[test]
    fn adaptive_clamps_and_halts_below_min() {
        let mut c = StepControl::new(TimeStep::Adaptive { cfl: 0.25, min: 1e-5, max: 1e-4 });
        assert_eq!(c.next_dt(&limits(0.0)).unwrap(), 1e-4);
        let err = c.next_dt(&Limits { c: 1e4, ..limits(0.0) }).unwrap_err();
        assert!(err.contains("fell below solver.time_step.min"), "{err}");
    }

    #[test]
    fn fixed_steps_are_substepped_when_too_large() {
        let mut c = StepControl::new(TimeStep::Fixed { dt: 1e-3, cfl: 0.25 });
        let l = limits(0.0); // stable limit 1.25e-4 s
        let mut total = 0.0;
        let mut n = 0;
        loop {
            total += c.next_dt(&l).unwrap();
            n += 1;
            if c.remaining == 0.0 {
                break;
            }
        }
        assert!((total - 1e-3).abs() < 1e-9);
        assert_eq!(n, 8);
        assert_eq!(c.substeps, 7);
    }

    #[test]
    fn an_interval_is_cut_into_equal_substeps() {
        // 1e-3 s at a limit of 3e-4 s: four steps of 2.5e-4 s, not three of 3e-4 s and
        // a remainder of 1e-4 s.
        let mut c = StepControl::new(TimeStep::Fixed { dt: 1e-3, cfl: 0.25 });
        let l = Limits { c: 0.25 * 0.02 / 3e-4, ..limits(0.0) };
        let steps: Vec<Real> = (0..4).map(|_| c.next_dt(&l).unwrap()).collect();
        assert_eq!(c.remaining, 0.0);
        for s in steps {
            assert!((s - 2.5e-4).abs() < 1e-9, "{s}");
        }
    }
}
