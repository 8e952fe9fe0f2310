//! What a scheme is: the pressure solver a scene uses (`solver.method`), which
//! orders the stages of a step. Exactly one per scene. A scheme drives the backend
//! through [`Stages`], so every backend steps a scene the same way, and the clock
//! ([`crate::clock::Clock`]) chooses dt and applies the guard between the stages.
//! The schemes themselves are in `crate::schemes`, listed in [`crate::registry`].
//!
//! - [`SchemeDef`]: a scheme's declaration (its step, its passes, its settings).
//! - [`Iterate`]: runs passes until a residual reduction falls below a tolerance,
//!   with at most one small readback per convergence check (solvers that iterate);
//!   sums a solve needs between its passes (a conjugate gradient's dot products)
//!   stay on the device ([`Op::Sum`]).
//! - [`velocity_solves`]: the modules' implicit velocity updates after a kick
//!   (implicit viscosity), which every scheme runs at the same point of its step.

use crate::clock::Clock;
use crate::cpu::CpuPass;
use crate::guard::{Halted, Measures};
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::plan::Stage;
use crate::scene::Scene;
use crate::scene::sections::SectionDef;

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
    /// The sum of attribute `attr` into element `slot` of attribute `into` (a
    /// solver's scalars, read by its next passes): no readback, the value stays
    /// where the passes run.
    fn sum_into(&mut self, attr: &'static str, into: &'static str, slot: u32);
    /// `v = (v + dt a) keep`.
    fn kick(&mut self, dt: Real, keep: Real);
    /// `x += dt v`, then the walls' non-penetration constraints.
    fn drift(&mut self, dt: Real);
    /// Sets the sweep index passes read during a swept iteration (a Gauss-Seidel
    /// colour; see [`Iterate::sweeps`]).
    fn sweep(&mut self, k: u32);
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
    /// The square root of the sum (a norm, from squares summed per element).
    Norm,
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

impl ReduceOp {
    /// Lower-case name, as in messages (`mean density_error`).
    pub fn name(self) -> &'static str {
        match self {
            ReduceOp::Sum => "sum of",
            ReduceOp::Mean => "mean",
            ReduceOp::Norm => "square root of the summed",
            ReduceOp::Max => "largest",
            ReduceOp::MaxAbs => "largest magnitude of",
            ReduceOp::Outside { .. } => "count out of range of",
        }
    }
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
    /// The solve's name.
    pub name: &'static str,
    /// Iterations run.
    pub iterations: u32,
    /// The last residual measured.
    pub residual: f64,
}

/// One operation of an iterative solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    /// A plan pass (of stage [`crate::plan::Stage::Solve`]), by name.
    Pass(&'static str),
    /// The sum of attribute `attr` into element `slot` of attribute `into`
    /// ([`Stages::sum_into`]).
    Sum {
        /// The summed attribute (one f32 per element).
        attr: &'static str,
        /// The solver's scalars.
        into: &'static str,
        /// The element of `into` written.
        slot: u32,
    },
}

impl Op {
    /// Runs the operation.
    pub fn run(self, s: &mut dyn Stages, dt: Real) {
        match self {
            Op::Pass(name) => s.run_pass(name, dt),
            Op::Sum { attr, into, slot } => s.sum_into(attr, into, slot),
        }
    }
}

/// Runs passes until a residual is at most a tolerance: PySPH's
/// `Group(iterate=True, min_iterations, max_iterations)` and the loop of every
/// solver that iterates (DFSPH's two solves, implicit viscosity, the position solves of
/// [`crate::position_solve`]).
///
/// `start` runs once (a warm start, the first residual), then the residual is
/// checked before each iteration: a solve already within its tolerance after
/// `start` runs `min` iterations and no more.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iterate {
    /// The solve's name, in step reports and statistics.
    pub name: &'static str,
    /// Operations run once before the first check.
    pub start: &'static [Op],
    /// The operations of one iteration, in order.
    pub iteration: &'static [Op],
    /// The residual, reduced after `start` and after each iteration.
    pub residual: Reduction,
    /// Converged at or below this residual.
    pub tolerance: f64,
    /// Iterations always run.
    pub min: u32,
    /// Iterations at most; not converged by then is an error naming the residual.
    pub max: u32,
    /// Iterations between two residual checks (each a small readback on a GPU).
    pub check_every: u32,
    /// Sweeps per iteration: the iteration's operations run this many times, the
    /// passes seeing the sweep index `0 .. sweeps` ([`Stages::sweep`]; e.g. one
    /// sweep per colour of a coloured Gauss-Seidel iteration). 1 for most solves.
    pub sweeps: u32,
    /// The most sweeps a live change may set (at least `sweeps`): what a GPU's
    /// sweep indices are allocated for.
    pub max_sweeps: u32,
}

impl Iterate {
    /// Runs the solve; the error says how far from converged it stopped.
    pub fn run(&self, s: &mut dyn Stages, dt: Real) -> Result<Solve, String> {
        for op in self.start {
            op.run(s, dt);
        }
        let mut residual = f64::INFINITY;
        for k in 0..=self.max {
            if k >= self.min && (k % self.check_every.max(1) == 0 || k == self.max) {
                residual = s.reduce(&self.residual)?;
                if residual.is_nan() {
                    return Err(format!("{}: the residual is not a number after {k} iterations", self.name));
                }
                if residual <= self.tolerance {
                    return Ok(Solve { name: self.name, iterations: k, residual });
                }
            }
            if k == self.max {
                break;
            }
            for sweep in 0..self.sweeps.max(1) {
                s.sweep(sweep);
                for op in self.iteration {
                    op.run(s, dt);
                }
            }
        }
        Err(format!(
            "{} did not converge in {} iterations: {} {} {residual:.3e} above the tolerance {:.3e}",
            self.name,
            self.max,
            self.residual.op.name(),
            self.residual.attr,
            self.tolerance
        ))
    }
}

/// Runs the model's velocity solves (implicit updates of the velocities after a
/// kick of `dt`, such as implicit viscosity) in the order the modules declared
/// them; a solve that does not converge halts the scene.
pub fn velocity_solves(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    let solves = s.model().velocity_solves.clone();
    solves.iter().map(|v| v.run(s, dt).map_err(|e| clock.halt(e, None))).collect()
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

/// The attribute a scheme with [`SchemeDef::pressure_terms`] writes: `p / rho^2`
/// of each particle (m^5/(kg s^2)).
pub const PRESSURE_TERM: &str = "pterm";

/// A scheme.
#[derive(Debug)]
pub struct SchemeDef {
    /// Name, as `solver.method` has it.
    pub id: &'static str,
    /// What it does.
    pub about: &'static str,
    /// Its settings: keys of the scene's `solver` section it owns (`dfsph`).
    pub settings: &'static [SectionDef],
    /// Whether its pressure force is the SPH gradient of the pressure terms
    /// `p / rho^2` it writes into [`PRESSURE_TERM`] before the force stage, for the
    /// force pass to add in its neighbour loop (WCSPH); otherwise it solves
    /// pressure itself (DFSPH).
    pub pressure_terms: bool,
    /// Checks its settings (`chosen`: the scene's scheme is this one; settings of a
    /// scheme the scene does not use are refused, naming the scheme they need).
    pub validate: fn(&Scene, bool, &mut crate::scene::validate::Checker),
    /// Its attributes, passes and constants.
    pub build: fn(&Scene, &mut ModelBuilder) -> Result<(), BuildError>,
    /// Takes new tunable settings from the scene (tolerances).
    pub retune: fn(&Scene, &mut Model),
    /// Its CPU passes, by pass name.
    pub cpu: &'static [(&'static str, &'static dyn CpuPass)],
    /// One step.
    pub step: fn(&mut Clock, &mut dyn Stages) -> Result<StepReport, Halted>,
    /// Where in its step the modules' position solves run.
    pub position_solves: crate::position_solve::When,
    /// The signal speed of the CFL condition (m/s): the speed of sound for WCSPH, 0
    /// for an incompressible scheme (the flow speed alone limits its steps).
    pub signal_speed: fn(&Model) -> Real,
}

/// Every scheme.
pub fn all() -> Vec<&'static SchemeDef> {
    crate::registry::SCHEMES.to_vec()
}

/// The scheme called `id`.
pub fn find(id: &str) -> Option<&'static SchemeDef> {
    all().into_iter().find(|s| s.id == id)
}

/// The scheme a scene's `solver.method` names (validated when it was loaded).
pub fn of(scene: &Scene) -> &'static SchemeDef {
    find(&scene.solver.method).unwrap_or_else(|| panic!("no scheme {:?}: scenes are validated", scene.solver.method))
}

/// Every scheme's settings (keys of `solver`).
pub fn settings() -> Vec<SectionDef> {
    all().iter().flat_map(|s| s.settings.iter().copied()).collect()
}
