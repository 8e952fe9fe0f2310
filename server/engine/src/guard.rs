//! The stability guard: a scene that goes non-finite, over-compressed, too fast
//! or out of its domain halts with a reason instead of producing garbage.

use serde::{Deserialize, Serialize};

/// Why and where a scene stopped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[error("halted at step {step}, t = {time:.6} s: {reason}{}", particle.map(|p| format!(" (particle {p})")).unwrap_or_default())]
pub struct Halted {
    /// Step number at which the check failed.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// What went wrong, with the measured value and the bound.
    pub reason: String,
    /// The particle (stable id) that crossed the bound, when one did.
    pub particle: Option<u32>,
}

/// A range a module's state attribute must stay in (a temperature between absolute
/// zero and a bound the module states); leaving it, or going non-finite, halts the
/// scene naming the particle. Checked after every evaluation on both backends, with
/// one small readback on a GPU.
#[derive(Debug, Clone, PartialEq)]
pub struct Bound {
    /// The attribute (one f32 per particle).
    pub attr: &'static str,
    /// What it is, for the message ("temperature").
    pub what: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Smallest and largest allowed value.
    pub min: f32,
    /// Largest allowed value.
    pub max: f32,
}

impl Bound {
    /// The halt reason for `value` outside the bound.
    pub fn reason(&self, value: f32) -> String {
        let (what, unit) = (self.what, self.unit);
        if value.is_finite() {
            format!("{what} {value} {unit} is outside its range [{}, {}] {unit}", self.min, self.max)
        } else {
            format!("non-finite {what} ({value}): the simulation diverged")
        }
    }
}

/// The first index of `values` outside `[min, max]` or not finite, with its value.
pub fn first_outside(values: &[f32], min: f32, max: f32) -> Option<(u32, f32)> {
    values.iter().position(|v| !(min..=max).contains(v)).map(|i| (i as u32, values[i]))
}

/// Per-step measurements the guard and the time step control need, reduced
/// over all particles.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Measures {
    /// Largest squared speed (m^2/s^2) and its particle index.
    pub max_speed2: (f32, u32),
    /// Largest squared acceleration (m^2/s^4).
    pub max_accel2: f32,
    /// Largest compression `(rho - rho0)/rho0` and its particle index.
    pub max_compression: (f32, u32),
    /// Sum of `max(rho - rho0, 0)/rho0` over particles.
    pub sum_compression: f64,
    /// First particle index with a non-finite value, if any.
    pub non_finite: Option<u32>,
    /// First particle index outside the domain, if any.
    pub outside: Option<u32>,
}

impl Measures {
    /// Combines the measures of two disjoint particle sets.
    pub fn merge(self, o: Measures) -> Measures {
        let max_by = |a: (f32, u32), b: (f32, u32)| if b.0 > a.0 { b } else { a };
        Measures {
            max_speed2: max_by(self.max_speed2, o.max_speed2),
            max_accel2: self.max_accel2.max(o.max_accel2),
            max_compression: max_by(self.max_compression, o.max_compression),
            sum_compression: self.sum_compression + o.sum_compression,
            non_finite: self.non_finite.or(o.non_finite),
            outside: self.outside.or(o.outside),
        }
    }

    /// The first violated bound as (reason, particle index), if any.
    pub fn violation(&self, max_compression: f32, max_speed: f32) -> Option<(String, u32)> {
        if let Some(i) = self.non_finite {
            return Some(("non-finite position, velocity or density (the simulation diverged)".into(), i));
        }
        let speed = self.max_speed2.0.sqrt();
        if speed > max_speed {
            return Some((
                format!("speed {speed:.3} m/s exceeds guard.max_speed = {max_speed:.3} m/s"),
                self.max_speed2.1,
            ));
        }
        if self.max_compression.0 > max_compression {
            return Some((
                format!(
                    "density deviation {:.1} % exceeds guard.max_compression = {:.1} %",
                    self.max_compression.0 * 100.0,
                    max_compression * 100.0
                ),
                self.max_compression.1,
            ));
        }
        if let Some(i) = self.outside {
            return Some(("particle left the simulation domain".into(), i));
        }
        None
    }
}
