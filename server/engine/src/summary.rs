//! The summary of a run, as written by `floe run --summary FILE.json`.

use crate::simulation::{Measure, Simulation, SolveStats};
use serde::Serialize;
use std::collections::BTreeMap;

/// What a finished (or halted) run did and what it cost.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Scene name.
    pub scene: String,
    /// Backend that stepped it.
    pub backend: String,
    /// Fluid particles.
    pub particles: usize,
    /// Steps taken.
    pub steps: u64,
    /// Sub-steps forced by a fixed time step above the stable limit.
    pub substeps: u64,
    /// Simulated time (s).
    pub simulated_seconds: f64,
    /// Wall-clock time of the stepping (s), exports excluded.
    pub wall_seconds: f64,
    /// Particles times steps per wall second.
    pub particle_steps_per_second: f64,
    /// Smallest, mean and largest dt (s).
    pub dt_min: f64,
    /// Mean dt (s).
    pub dt_mean: f64,
    /// Largest dt (s).
    pub dt_max: f64,
    /// Largest compression `(rho - rho0)/rho0` seen.
    pub max_density_deviation: f64,
    /// Mean over steps of the mean compression.
    pub mean_density_deviation: f64,
    /// Largest particle speed seen (m/s).
    pub max_speed: f64,
    /// Each iterative solve of the scheme (DFSPH's `dfsph.divergence`, `dfsph.density`):
    /// mean and most iterations per step, the last residual, total iterations. Empty for
    /// schemes that do not iterate.
    pub solves: BTreeMap<String, SolveStats>,
    /// What the scene's modules report at the end of the run (`snow.runout`,
    /// `heat.mean_temperature`, ...), with units.
    pub measures: Vec<Measure>,
    /// Why the run halted, if it did (the message a user sees).
    pub halted: Option<String>,
}

impl Summary {
    /// Summarises `sim` after `wall_seconds` of stepping.
    pub fn new(sim: &Simulation, wall_seconds: f64) -> Self {
        let s = sim.stats();
        let steps = sim.steps();
        Self {
            scene: sim.scene().name.clone(),
            backend: sim.backend_name().into(),
            particles: sim.particle_count(),
            steps,
            substeps: sim.substeps(),
            simulated_seconds: sim.time(),
            wall_seconds,
            particle_steps_per_second: sim.particle_count() as f64 * steps as f64 / wall_seconds.max(1e-9),
            dt_min: s.dt_min,
            dt_mean: s.dt_mean,
            dt_max: s.dt_max,
            max_density_deviation: s.max_density_deviation,
            mean_density_deviation: s.mean_density_deviation,
            max_speed: s.max_speed,
            solves: s.solves.clone(),
            measures: sim.measures(),
            halted: sim.halted().map(|h| h.to_string()),
        }
    }
}
