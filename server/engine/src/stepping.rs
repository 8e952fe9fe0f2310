//! The step sequence every backend shares, so CPU and GPU integrate, choose
//! their time step, guard and snapshot in exactly the same way; a backend
//! supplies only the particle passes ([`Passes`]).
//!
//! Integrators (velocities and positions of the sorted particle state):
//! - symplectic Euler: evaluate `a(x)`, then `v += dt a`, `x += dt v`;
//! - leap-frog kick-drift-kick (Verlet 1967; Monaghan 2005, Rep. Prog. Phys. 68,
//!   section 6): `v += dt/2 a`, `x += dt v`, evaluate, `v += dt/2 a`, reusing the
//!   previous step's measures to choose dt.
//!
//! XSPH is applied with the kick that follows an evaluation; damping multiplies
//! velocities by `exp(-rate dt)` until its end time.

use crate::backend::{Particles, StepReport};
use crate::eos::Eos;
use crate::guard::{Halted, Measures};
use crate::math::{Real, Vec3};
use crate::model::Model;
use crate::scene::Integrator;
use crate::snapshot::{Reader, SnapshotError, Writer};
use crate::timestep::{Limits, StepControl};
use floe_proto::Values;

/// The particle passes of one backend. Calls may be queued (a GPU records them
/// into a command buffer); [`Passes::evaluate`] returns once its measures are known.
pub trait Passes {
    /// The model being stepped (its current, possibly retuned, settings).
    fn model(&self) -> &Model;
    /// Re-sorts by cell, computes density, pressure and accelerations, and reduces
    /// the state to the guard's and the time step's measures; or says why the
    /// hardware could not (a lost GPU), which halts the scene.
    fn evaluate(&mut self) -> Result<Measures, String>;
    /// `v = (v + dt a) keep`, plus the XSPH correction when `with_xsph`.
    fn kick(&mut self, dt: Real, keep: Real, with_xsph: bool);
    /// `x += dt v`, then the walls' non-penetration constraints.
    fn drift(&mut self, dt: Real);
    /// The stable id of the particle in sorted slot `slot`.
    fn particle_id(&mut self, slot: u32) -> u32;
    /// Called after every step (a GPU submits the step's last passes).
    fn end_step(&mut self) {}
}

/// Where a run stands: time, steps, time-step control and the last measures.
#[derive(Debug, Clone)]
pub struct Clock {
    control: StepControl,
    time: f64,
    steps: u64,
    /// Measures of the last evaluation; `None` until the first one.
    measures: Option<Measures>,
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

    /// Follows a retuned model's time-step settings (a changed mode starts afresh).
    pub fn retune(&mut self, model: &Model) {
        if model.time_step != *self.control.mode() {
            self.control = StepControl::new(model.time_step);
        }
    }

    /// Evaluates and applies the stability guard.
    fn evaluate<P: Passes + ?Sized>(&mut self, s: &Settings, p: &mut P) -> Result<Measures, Halted> {
        let m = p.evaluate().map_err(|reason| self.halt(reason, None))?;
        if let Some((reason, slot)) = m.violation(s.max_compression, s.max_speed) {
            return Err(self.halt(reason, Some(p.particle_id(slot))));
        }
        self.measures = Some(m);
        Ok(m)
    }

    /// Advances one step of the `n` particles of `p` with its model's integrator.
    pub fn step<P: Passes + ?Sized>(&mut self, p: &mut P, n: usize) -> Result<StepReport, Halted> {
        let s = Settings::of(p.model());
        let keep = |dt: Real, time: f64| {
            let (rate, until) = s.damping;
            if rate > 0.0 && time < until { (-rate * dt).exp() } else { 1.0 }
        };
        let (dt, m) = match s.integrator {
            Integrator::SymplecticEuler => {
                let m = self.evaluate(&s, p)?;
                let dt = self.dt(&s, &m)?;
                p.kick(dt, keep(dt, self.time), true);
                p.drift(dt);
                (dt, m)
            }
            Integrator::Leapfrog => {
                let m0 = match self.measures {
                    Some(m) => m,
                    None => self.evaluate(&s, p)?,
                };
                let dt = self.dt(&s, &m0)?;
                p.kick(0.5 * dt, keep(0.5 * dt, self.time), false);
                p.drift(dt);
                let m = self.evaluate(&s, p)?;
                p.kick(0.5 * dt, keep(0.5 * dt, self.time), true);
                (dt, m)
            }
        };
        p.end_step();
        self.time += dt as f64;
        self.steps += 1;
        Ok(StepReport {
            dt,
            max_speed: m.max_speed2.0.sqrt(),
            max_compression: m.max_compression.0.max(0.0),
            mean_compression: (m.sum_compression / n.max(1) as f64) as f32,
        })
    }

    fn halt(&self, reason: String, particle: Option<u32>) -> Halted {
        Halted { step: self.steps, time: self.time, reason, particle }
    }

    fn dt(&mut self, s: &Settings, m: &Measures) -> Result<Real, Halted> {
        let limits = Limits { v_max: m.max_speed2.0.sqrt(), a_max: m.max_accel2.sqrt(), ..s.limits };
        self.control.next_dt(&limits).map_err(|reason| self.halt(reason, None))
    }

    /// Writes the clock and the sorted particle state (see [`crate::snapshot`]).
    pub fn save(&self, out: &mut Writer, state: &SortedState) {
        out.f64(self.time);
        out.u64(self.steps);
        out.f32(self.control.remaining());
        out.u64(self.control.substeps);
        out.u64(state.ids.len() as u64);
        for v in [&state.pos, &state.vel, &state.acc] {
            out.f32s(v.iter().flat_map(|x| x.to_array()).collect::<Vec<_>>().into_iter());
        }
        out.f32s(state.ids.iter().map(|&i| f32::from_bits(i)).collect::<Vec<_>>().into_iter());
        match &self.measures {
            None => out.u32(0),
            Some(m) => {
                out.u32(1);
                out.f32(m.max_speed2.0);
                out.u32(m.max_speed2.1);
                out.f32(m.max_accel2);
                out.f32(m.max_compression.0);
                out.u32(m.max_compression.1);
                out.f64(m.sum_compression);
            }
        }
    }

    /// Reads what [`Clock::save`] wrote for a scene of `n` particles, restoring
    /// the clock and returning the particle state.
    pub fn load(&mut self, r: &mut Reader<'_>, n: usize) -> Result<SortedState, SnapshotError> {
        let time = r.f64("time")?;
        let steps = r.u64("steps")?;
        let (remaining, substeps) = (r.f32("time step control")?, r.u64("time step control")?);
        let count = r.u64("particle count")?;
        if count != n as u64 {
            return Err(SnapshotError::Malformed(format!("{count} particles, the scene has {n}")));
        }
        let vecs = |v: Vec<f32>| v.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect::<Vec<_>>();
        let pos = vecs(r.f32s(3 * n, "positions")?);
        let vel = vecs(r.f32s(3 * n, "velocities")?);
        let acc = vecs(r.f32s(3 * n, "accelerations")?);
        let ids: Vec<u32> = r.f32s(n, "ids")?.into_iter().map(f32::to_bits).collect();
        let mut seen = vec![false; n];
        for &i in &ids {
            if i as usize >= n || std::mem::replace(&mut seen[i as usize], true) {
                return Err(SnapshotError::Malformed(format!("particle ids are not a permutation (id {i})")));
            }
        }
        let measures = match r.u32("measures flag")? {
            0 => None,
            1 => Some(Measures {
                max_speed2: (r.f32("measures")?, r.u32("measures")?),
                max_accel2: r.f32("measures")?,
                max_compression: (r.f32("measures")?, r.u32("measures")?),
                sum_compression: r.f64("measures")?,
                non_finite: None,
                outside: None,
            }),
            f => return Err(SnapshotError::Malformed(format!("measures flag {f}"))),
        };
        (self.time, self.steps, self.measures) = (time, steps, measures);
        self.control.restore(remaining, substeps);
        Ok(SortedState { pos, vel, acc, ids })
    }
}

/// The model's settings a step needs, copied so the passes can borrow the model.
#[derive(Debug, Clone, Copy)]
struct Settings {
    integrator: Integrator,
    damping: (Real, f64),
    max_compression: Real,
    max_speed: Real,
    /// The state-independent inputs of the stable limit.
    limits: Limits,
}

impl Settings {
    fn of(model: &Model) -> Self {
        let f = &model.fluid;
        Self {
            integrator: model.integrator,
            damping: model.damping,
            max_compression: model.max_compression,
            max_speed: model.max_speed,
            limits: Limits {
                h: 0.5 * model.kernel.support(),
                c: f.sound_speed,
                v_max: 0.0,
                a_max: 0.0,
                nu: f.viscosity.effective_nu(f.rho0),
            },
        }
    }
}

/// Particle state in sorted-slot order: what a snapshot holds.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SortedState {
    /// Positions (m).
    pub pos: Vec<Vec3>,
    /// Velocities (m/s).
    pub vel: Vec<Vec3>,
    /// Accelerations of the last evaluation (m/s^2).
    pub acc: Vec<Vec3>,
    /// The stable id of each slot.
    pub ids: Vec<u32>,
}

/// Output in identity order from sorted slots: `ids[k]` is slot k's particle.
/// `vel` must be given when `channels` has velocity, `rho` when it has density
/// or pressure (which comes from density through `eos`).
pub fn by_identity(
    channels: &[&str],
    ids: &[u32],
    pos: &[Vec3],
    vel: Option<&[Vec3]>,
    rho: Option<&[Real]>,
    eos: &Eos,
) -> Particles {
    fn scatter<T: Copy, U: Copy + Default>(ids: &[u32], src: &[T], f: impl Fn(T) -> U) -> Vec<U> {
        let mut out = vec![U::default(); src.len()];
        for (&id, &v) in ids.iter().zip(src) {
            out[id as usize] = f(v);
        }
        out
    }
    fn given<T>(what: &str, v: Option<T>) -> T {
        v.unwrap_or_else(|| panic!("by_identity: {what} was asked for but not given"))
    }
    let values = |name: &str| match name {
        "velocity" => Values::vectors(scatter(ids, given("velocity", vel), |v| v.to_array())),
        "density" => Values::scalars(scatter(ids, given("density", rho), |r| r)),
        "pressure" => Values::scalars(scatter(ids, given("density", rho), |r| eos.pressure(r))),
        other => panic!("by_identity: no channel {other}"),
    };
    Particles {
        set: crate::channels::PARTICLES.into(),
        positions: scatter(ids, pos, |v| v.to_array()),
        channels: channels.iter().map(|&c| (c.to_string(), values(c))).collect(),
    }
}
