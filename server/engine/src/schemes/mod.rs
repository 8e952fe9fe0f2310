//! Schemes: the pressure solver a scene uses (`solver.method`), which orders the
//! stages of a step. Exactly one per scene. A scheme drives the backend through
//! [`Stages`], so every backend steps a scene the same way, and the clock
//! ([`crate::clock::Clock`]) chooses dt and applies the guard between the stages.
//!
//! - [`wcsph`]: weakly compressible SPH, the first scheme.
//! - [`Iterate`]: runs a pass until a residual reduction falls below a tolerance,
//!   with at most one small readback per convergence check (solvers that iterate).

pub mod wcsph;

use crate::clock::Clock;
use crate::cpu::CpuPass;
use crate::guard::{Halted, Measures};
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::plan::Stage;
use crate::scene::{Method, Scene};

/// What a backend offers a scheme: the plan's stages and passes, the core's
/// reduction and integrator halves, and reductions for iterations. Calls may be
/// queued (a GPU records them); [`Stages::measure`] and [`Stages::reduce`] return
/// once their values are known.
pub trait Stages {
    /// The model being stepped (its current, possibly retuned, settings).
    fn model(&self) -> &Model;
    /// Runs every pass of `stage` in plan order, with the step's `dt` (s).
    fn run(&mut self, stage: Stage, dt: Real);
    /// Runs one pass of the plan by name (a solver's iteration).
    fn run_pass(&mut self, name: &str, dt: Real);
    /// The guard's and time step's reduction of the state; or why the hardware could
    /// not deliver it (a lost GPU), which halts the scene.
    fn measure(&mut self) -> Result<Measures, String>;
    /// Reduces an attribute to one number (one small readback on a GPU).
    fn reduce(&mut self, r: &Reduction) -> Result<f64, String>;
    /// `v = (v + dt a) keep`.
    fn kick(&mut self, dt: Real, keep: Real);
    /// `x += dt v`, then the walls' non-penetration constraints.
    fn drift(&mut self, dt: Real);
    /// The stable id of the particle in sorted slot `slot`.
    fn particle_id(&mut self, slot: u32) -> u32;
    /// The first slot whose value of `attr` is outside `[min, max]` or not finite,
    /// with that value (a guard found one: this path may be slow).
    fn first_outside(&mut self, attr: &str, min: Real, max: Real) -> Option<(u32, Real)>;
    /// Called after every step (a GPU submits the step's last passes).
    fn end_step(&mut self) {}
}

/// How a reduction combines an attribute's values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReduceOp {
    /// The sum.
    Sum,
    /// The mean.
    Mean,
    /// The largest value.
    Max,
    /// The largest magnitude.
    MaxAbs,
    /// How many values are outside `[min, max]` or not finite (a guard's bound).
    Outside {
        /// Smallest allowed value.
        min: Real,
        /// Largest allowed value.
        max: Real,
    },
}

/// An attribute reduced to one number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduction {
    /// The attribute (one f32 per element).
    pub attr: &'static str,
    /// How.
    pub op: ReduceOp,
}

/// What an iterative solve reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solve {
    /// The solve's name (its pass).
    pub name: &'static str,
    /// Iterations run.
    pub iterations: u32,
    /// The last residual measured.
    pub residual: f64,
}

/// Runs a pass until its residual is at most a tolerance: PySPH's
/// `Group(iterate=True, min_iterations, max_iterations)` and the loop of every
/// solver that iterates (DFSPH's two solves, implicit viscosity, shape matching).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iterate {
    /// The pass one iteration runs.
    pub pass: &'static str,
    /// The residual after an iteration.
    pub residual: Reduction,
    /// Converged at or below this residual.
    pub tolerance: f64,
    /// Iterations always run.
    pub min: u32,
    /// Iterations at most; not converged by then is an error naming the residual.
    pub max: u32,
    /// Iterations between two residual checks (each a small readback on a GPU).
    pub check_every: u32,
}

impl Iterate {
    /// Runs the iterations; the error says how far from converged the solve stopped.
    pub fn run(&self, s: &mut dyn Stages, dt: Real) -> Result<Solve, String> {
        let mut residual = f64::INFINITY;
        for k in 1..=self.max {
            s.run_pass(self.pass, dt);
            if k >= self.min && (k % self.check_every.max(1) == 0 || k == self.max) {
                residual = s.reduce(&self.residual)?;
                if residual <= self.tolerance {
                    return Ok(Solve { name: self.pass, iterations: k, residual });
                }
            }
        }
        Err(format!(
            "{} did not converge in {} iterations: residual {residual:.3e} above the tolerance {:.3e}",
            self.pass, self.max, self.tolerance
        ))
    }
}

/// What one step did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepReport {
    /// Time step taken (s).
    pub dt: f32,
    /// Largest speed (m/s).
    pub max_speed: f32,
    /// Largest compression `(rho - rho0)/rho0`.
    pub max_compression: f32,
    /// Mean compression over particles (surface deficits count as 0).
    pub mean_compression: f32,
    /// The scheme's iterative solves, if it iterates.
    pub solves: Vec<Solve>,
}

/// A scheme.
#[derive(Debug)]
pub struct SchemeDef {
    /// Name, as `solver.method` has it.
    pub id: &'static str,
    /// What it does.
    pub about: &'static str,
    /// Its attributes, passes and constants.
    pub build: fn(&Scene, &mut ModelBuilder) -> Result<(), BuildError>,
    /// Its CPU passes, by pass name.
    pub cpu: &'static [(&'static str, &'static dyn CpuPass)],
    /// One step.
    pub step: fn(&mut Clock, &mut dyn Stages) -> Result<StepReport, Halted>,
    /// The signal speed of the CFL condition (m/s): the speed of sound for WCSPH.
    pub signal_speed: fn(&Model) -> Real,
}

/// Every scheme.
pub fn all() -> Vec<&'static SchemeDef> {
    vec![&wcsph::SCHEME]
}

/// The scheme a scene's `solver.method` names.
pub fn of(scene: &Scene) -> &'static SchemeDef {
    match scene.solver.method {
        Method::Wcsph => &wcsph::SCHEME,
    }
}
