//! Where a run stands (time, steps, the time-step control, the last measures), and
//! the checks a scheme makes between the stages of a step: evaluating with the
//! stability guard, choosing dt from the stable limits, the damping factor.

use crate::guard::{Halted, Measures};
use crate::math::Real;
use crate::model::Model;
use crate::plan::Stage;
use crate::scheme::{ReduceOp, Reduction, Stages, StepReport};
use crate::timestep::{Limits, StepControl};
use serde::{Deserialize, Serialize};

/// Where a run stands.
#[derive(Debug, Clone)]
pub struct Clock {
    control: StepControl,
    time: f64,
    steps: u64,
    /// Measures of the last evaluation; `None` until the first one.
    measures: Option<Measures>,
}

/// The clock as a snapshot holds it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClockState {
    /// Simulated time (s), as f64 bits.
    pub time: u64,
    /// Steps taken.
    pub steps: u64,
    /// Time left in the current fixed interval (s), as f32 bits.
    pub remaining: u32,
    /// Fixed-mode sub-steps taken.
    pub substeps: u64,
    /// The last evaluation's measures, if any.
    pub measures: Option<MeasuresState>,
}

/// [`Measures`] in a snapshot (floats as bits, so restores are exact).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MeasuresState {
    /// Largest squared speed (bits) and its slot.
    pub max_speed2: (u32, u32),
    /// Largest squared acceleration (bits).
    pub max_accel2: u32,
    /// Largest compression (bits) and its slot.
    pub max_compression: (u32, u32),
    /// Sum of compressions (bits).
    pub sum_compression: u64,
}

impl Clock {
    /// A run of `model` at t = 0.
    pub fn new(model: &Model) -> Self {
        Self { control: StepControl::new(model.time_step), time: 0.0, steps: 0, measures: None }
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Fixed-mode sub-steps taken.
    pub fn substeps(&self) -> u64 {
        self.control.substeps
    }

    /// The measures of the last evaluation, if there was one.
    pub fn measures(&self) -> Option<Measures> {
        self.measures
    }

    /// Follows a retuned model's time-step settings (a changed mode starts afresh).
    pub fn retune(&mut self, model: &Model) {
        if model.time_step != *self.control.mode() {
            self.control = StepControl::new(model.time_step);
        }
    }

    /// Runs `stages` on `s`, measures, and applies the stability guard.
    pub fn evaluate(&mut self, s: &mut dyn Stages, stages: &[Stage]) -> Result<Measures, Halted> {
        for &stage in stages {
            s.run(stage, 0.0);
        }
        let m = s.measure().map_err(|reason| self.halt(reason, None))?;
        let model = s.model();
        if let Some((reason, slot)) = m.violation(model.max_compression, model.max_speed) {
            return Err(self.halt(reason, Some(s.particle_id(slot))));
        }
        let bounds = model.bounds.clone();
        for b in &bounds {
            let outside = s.reduce(&Reduction { attr: b.attr, op: ReduceOp::Outside { min: b.min, max: b.max } });
            let outside = outside.map_err(|reason| self.halt(reason, None))?;
            if outside > 0.0
                && let Some((slot, value)) = s.first_outside(b.attr, b.min, b.max)
            {
                return Err(self.halt(b.reason(value), Some(s.particle_id(slot))));
            }
        }
        self.measures = Some(m);
        Ok(m)
    }

    /// The next dt from the stable limits of `m` and the pressure's signal speed `c_p`
    /// (m/s; 0 for a scheme whose pressure is not a constraint's, [`Limits::c_p`]), or
    /// the halt when it is too small.
    pub fn dt(&mut self, model: &Model, m: &Measures, c_p: Real) -> Result<Real, Halted> {
        let module = model.modules.iter().filter_map(|d| (d.dt_limit)(model)).fold(
            None,
            |best: Option<(&'static str, Real)>, l| match best {
                Some(b) if b.1 <= l.1 => Some(b),
                _ => Some(l),
            },
        );
        let limits = Limits {
            h: 0.5 * model.kernel.support(),
            // Without SPH particles (snowfall alone, or before a fluid's first births)
            // sound sets no limit.
            c: if model.particle_count() == 0 { 0.0 } else { (model.scheme.signal_speed)(model) },
            v_max: m.max_speed2.0.sqrt(),
            c_p,
            a_max: m.max_accel2.sqrt(),
            module,
        };
        self.control.next_dt(&limits).map_err(|reason| self.halt(reason, None))
    }

    /// The damping factor of a kick of `dt` starting now: `exp(-rate dt)` until the
    /// damping's end time, else 1.
    pub fn keep(&self, model: &Model, dt: Real) -> Real {
        let (rate, until) = model.damping;
        if rate > 0.0 && self.time < until { (-rate * dt).exp() } else { 1.0 }
    }

    /// Ends a step of `dt` for `n` particles: advances the clock and reports.
    pub fn advance(&mut self, dt: Real, m: &Measures, n: usize, solves: Vec<crate::scheme::Solve>) -> StepReport {
        self.time += dt as f64;
        self.steps += 1;
        StepReport {
            dt,
            max_speed: m.max_speed2.0.sqrt(),
            max_compression: m.max_compression.0.max(0.0),
            mean_compression: (m.sum_compression / n.max(1) as f64) as f32,
            solves,
        }
    }

    /// A halt at the current step.
    pub fn halt(&self, reason: String, particle: Option<u32>) -> Halted {
        Halted { step: self.steps, time: self.time, reason, particle }
    }

    /// The clock's state for a snapshot.
    pub fn state(&self) -> ClockState {
        ClockState {
            time: self.time.to_bits(),
            steps: self.steps,
            remaining: self.control.remaining().to_bits(),
            substeps: self.control.substeps,
            measures: self.measures.map(|m| MeasuresState {
                max_speed2: (m.max_speed2.0.to_bits(), m.max_speed2.1),
                max_accel2: m.max_accel2.to_bits(),
                max_compression: (m.max_compression.0.to_bits(), m.max_compression.1),
                sum_compression: m.sum_compression.to_bits(),
            }),
        }
    }

    /// Takes a snapshot's clock state.
    pub fn restore(&mut self, s: &ClockState) {
        self.time = f64::from_bits(s.time);
        self.steps = s.steps;
        self.control.restore(f32::from_bits(s.remaining), s.substeps);
        self.measures = s.measures.map(|m| Measures {
            max_speed2: (f32::from_bits(m.max_speed2.0), m.max_speed2.1),
            max_accel2: f32::from_bits(m.max_accel2),
            max_compression: (f32::from_bits(m.max_compression.0), m.max_compression.1),
            sum_compression: f64::from_bits(m.sum_compression),
            non_finite: None,
            outside: None,
        });
    }
}
