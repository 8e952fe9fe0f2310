//! A scene being simulated: a backend, the scheme stepping it and the clock, plus
//! the run's statistics and halt state.

use crate::backend::{Backend, Particles, StepReport};
use crate::channels::{ChannelSpec, PARTICLE_SET, SetSpec};
use crate::clock::Clock;
use crate::cpu::CpuBackend;
use crate::guard::Halted;
use crate::model::{BuildError, Model};
use crate::scene::Scene;
use crate::snapshot::{self, SnapshotError};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Statistics over every step taken so far.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RunStats {
    /// Smallest dt (s).
    pub dt_min: f64,
    /// Mean dt (s).
    pub dt_mean: f64,
    /// Largest dt (s).
    pub dt_max: f64,
    /// Largest compression `(rho - rho0)/rho0` seen at any step.
    pub max_density_deviation: f64,
    /// Mean over steps of the per-step mean compression.
    pub mean_density_deviation: f64,
    /// Largest speed seen (m/s).
    pub max_speed: f64,
    /// Per iterative solve of the scheme: iterations and residuals.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub solves: BTreeMap<String, SolveStats>,
    /// Sum of dt over steps (s), for the mean.
    #[serde(skip)]
    dt_sum: f64,
    /// Sum of the per-step mean compressions, for the mean.
    #[serde(skip)]
    compression_sum: f64,
}

/// Iterations and residuals of one iterative solve over the run.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveStats {
    /// Mean iterations per step.
    pub mean_iterations: f64,
    /// Most iterations in one step.
    pub max_iterations: u32,
    /// The residual the last step reached.
    pub last_residual: f64,
    /// Total iterations.
    pub total_iterations: u64,
}

/// A named value a scene reports (a solver's iterations, a front position, the
/// total heat), in SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Measure {
    /// Name, `module.quantity` for a module's.
    pub name: String,
    /// Value.
    pub value: f64,
    /// SI unit, empty when dimensionless.
    pub unit: String,
}

impl Measure {
    /// A measure called `name`.
    pub fn new(name: impl Into<String>, value: f64, unit: &str) -> Self {
        Self { name: name.into(), value, unit: unit.into() }
    }
}

/// The statistics with the running sums behind the means, as a snapshot saves them.
#[derive(Debug, Serialize, Deserialize)]
struct SavedStats {
    stats: RunStats,
    dt_sum: f64,
    compression_sum: f64,
}

/// A running scene.
pub struct Simulation {
    scene: Scene,
    backend: Box<dyn Backend>,
    clock: Clock,
    stats: RunStats,
    halted: Option<Halted>,
}

impl std::fmt::Debug for Simulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("scene", &self.scene.name)
            .field("backend", &self.backend.name())
            .field("time", &self.clock.time())
            .field("halted", &self.halted)
            .finish()
    }
}

/// Builds the backend a scene runs on from its model: how a server chooses
/// between the CPU and a GPU once, for every scene it creates or restores.
pub type BackendFactory = dyn Fn(Model) -> Result<Box<dyn Backend>, BuildError> + Send + Sync;

/// The CPU backend as a [`BackendFactory`].
pub fn cpu_backend(model: Model) -> Result<Box<dyn Backend>, BuildError> {
    Ok(Box::new(CpuBackend::new(model)))
}

impl Simulation {
    /// Builds a scene on the CPU backend.
    pub fn new_cpu(scene: Scene) -> Result<Self, BuildError> {
        Self::new(scene, &cpu_backend)
    }

    /// Builds a scene on the backend `make` builds.
    pub fn new(scene: Scene, make: &BackendFactory) -> Result<Self, BuildError> {
        let model = Model::build(&scene)?;
        Ok(Self::with_backend(scene, make(model)?))
    }

    /// Wraps an already built backend.
    pub fn with_backend(scene: Scene, backend: Box<dyn Backend>) -> Self {
        let clock = Clock::new(backend.model());
        Self { scene, backend, clock, stats: RunStats::default(), halted: None }
    }

    /// The scene as given.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The model being stepped.
    pub fn model(&self) -> &Model {
        self.backend.model()
    }

    /// The backend (to compare backends pass by pass, or to inspect allocations).
    pub fn backend(&self) -> &dyn Backend {
        &*self.backend
    }

    /// The backend, to drive its stages directly (tests that compare backends pass by pass).
    pub fn backend_mut(&mut self) -> &mut dyn Backend {
        &mut *self.backend
    }

    /// The backend's name.
    pub fn backend_name(&self) -> &'static str {
        self.backend.name()
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.clock.time()
    }

    /// The longest step the scene may take (s): the adaptive control's `max`, or the
    /// fixed interval (sub-steps are shorter). Reaching a time `T` ahead takes at
    /// least `T / largest_step()` steps.
    pub fn largest_step(&self) -> f64 {
        match self.model().time_step {
            crate::scene::TimeStep::Adaptive { max, .. } => f64::from(max),
            crate::scene::TimeStep::Fixed { dt, .. } => f64::from(dt),
        }
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.clock.steps()
    }

    /// Sub-steps taken by fixed time-step mode.
    pub fn substeps(&self) -> u64 {
        self.clock.substeps()
    }

    /// Number of SPH particles.
    pub fn particle_count(&self) -> usize {
        self.backend.particle_count()
    }

    /// Mass of a particle of material 0 (kg; 0 in a scene without SPH particles).
    pub fn particle_mass(&self) -> f32 {
        self.model().materials.iter().next().map_or(0.0, |m| m.mass)
    }

    /// The simulation domain (m).
    pub fn domain(&self) -> crate::math::Aabb {
        self.model().domain
    }

    /// The channels this scene offers, in the order clients are told about them.
    pub fn channels(&self) -> Vec<ChannelSpec> {
        self.model().channels.clone()
    }

    /// The scene's particle sets with their counts (a part's members now: this reads
    /// the particles' materials back).
    pub fn sets(&self) -> Vec<(SetSpec, usize)> {
        let count = |s: &SetSpec| match s.kind {
            Some(_) => self.read_set(s, &[]).positions.len(),
            None => self.model().layout.count(s.space),
        };
        self.model().sets.iter().map(|s| (*s, count(s))).collect()
    }

    /// Why the scene stopped, if it did.
    pub fn halted(&self) -> Option<&Halted> {
        self.halted.as_ref()
    }

    /// Run statistics so far.
    pub fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// The named values the scene reports with its statistics: the run's largest
    /// density deviation and speed, the sub-steps a fixed step above the stable
    /// limit took (where it did), each iterative solve's iterations and last
    /// residual, and what each module measures (its [`crate::module::ModuleDef::measures`]).
    /// Module measures may read state back from the device: call it at most a few
    /// times a second.
    pub fn measures(&self) -> Vec<Measure> {
        let s = &self.stats;
        let mut out = vec![
            Measure::new("max_density_deviation", s.max_density_deviation, ""),
            Measure::new("max_speed", s.max_speed, "m/s"),
        ];
        // A fixed step above the stable limit is taken in sub-steps: say how many.
        if self.substeps() > 0 {
            out.push(Measure::new("substeps", self.substeps() as f64, ""));
        }
        for (name, solve) in &s.solves {
            out.push(Measure::new(format!("{name}.mean_iterations"), solve.mean_iterations, ""));
            out.push(Measure::new(format!("{name}.max_iterations"), f64::from(solve.max_iterations), ""));
            out.push(Measure::new(format!("{name}.last_residual"), solve.last_residual, ""));
        }
        for m in &self.backend.model().modules {
            out.extend((m.measures)(self));
        }
        out
    }

    /// Copies out positions and the requested channels of the SPH particles, in
    /// identity order.
    pub fn read(&self, channels: &[&str]) -> Particles {
        self.backend.read_set(&PARTICLE_SET, channels)
    }

    /// Copies out positions and the requested channels of particle set `set`.
    pub fn read_set(&self, set: &SetSpec, channels: &[&str]) -> Particles {
        self.backend.read_set(set, channels)
    }

    /// Per-kernel device time (see [`Backend::kernel_times`]).
    pub fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.backend.kernel_times()
    }

    /// Bytes held in device memory (see [`Backend::device_memory`]).
    pub fn device_memory(&self) -> Option<u64> {
        self.backend.device_memory()
    }

    /// [`Simulation::read_set`] with positions on `grid` (see [`Backend::read_on_grid`]).
    pub fn read_on_grid(&self, set: &SetSpec, channels: &[&str], grid: &crate::quantize::PositionGrid) -> Particles {
        self.backend.read_on_grid(set, channels, grid)
    }

    /// One step. After a halt every call returns the same [`Halted`].
    pub fn step(&mut self) -> Result<StepReport, Halted> {
        if let Some(h) = &self.halted {
            return Err(h.clone());
        }
        let step = self.backend.model().scheme.step;
        // The whole step on a worker of the thread pool: its parallel passes then
        // split work among the workers without waking the caller's thread and
        // parking it again for each one (a scene of a few thousand particles spent
        // a fifth of its time so).
        let (clock, backend) = (&mut self.clock, self.backend.as_mut());
        match rayon::scope(|_| step(clock, backend)) {
            Ok(r) => {
                self.record(&r);
                let (steps, time) = (self.clock.steps(), self.clock.time());
                if let Err(reason) = crate::population::after_step(self.backend.as_mut(), steps, time, r.dt) {
                    return Err(self.fail(reason));
                }
                Ok(r)
            }
            Err(h) => {
                self.halted = Some(h.clone());
                Err(h)
            }
        }
    }

    /// Halts the scene for a failure outside the physics (a backend that failed
    /// unexpectedly); later steps return this halt.
    pub fn fail(&mut self, reason: String) -> Halted {
        let h = Halted { step: self.steps(), time: self.time(), reason, particle: None };
        self.halted = Some(h.clone());
        h
    }

    /// Steps until simulated time reaches `t_end` (s), calling `each` after every step.
    pub fn run_until(&mut self, t_end: f64, mut each: impl FnMut(&Simulation, &StepReport)) -> Result<(), Halted> {
        while self.time() < t_end {
            let r = self.step()?;
            each(self, &r);
        }
        Ok(())
    }

    /// Changes tunable settings with `key=value` overrides (see
    /// [`crate::scene::tunable`]); takes effect from the next step.
    pub fn set_parameters(&mut self, overrides: &[String]) -> Result<(), crate::scene::load::SceneError> {
        let next = crate::scene::tunable::apply(&self.scene, overrides)?;
        self.backend.retune(&next);
        self.clock.retune(self.backend.model());
        self.scene = next;
        Ok(())
    }

    /// The complete state as bytes (see [`crate::snapshot`]).
    pub fn snapshot(&self) -> Vec<u8> {
        let stats = SavedStats {
            stats: self.stats.clone(),
            dt_sum: self.stats.dt_sum,
            compression_sum: self.stats.compression_sum,
        };
        snapshot::write(&snapshot::Parts {
            scene: serde_json::to_string(&self.scene).expect("scenes serialise"),
            stats: serde_json::to_string(&stats).expect("statistics serialise"),
            halt: serde_json::to_string(&self.halted).expect("halts serialise"),
            clock: self.clock.state(),
            sections: self.backend.state(),
        })
    }

    /// Rebuilds a scene from a snapshot, on the CPU backend.
    pub fn restore(bytes: &[u8]) -> Result<Self, SnapshotError> {
        Self::restore_on(bytes, &cpu_backend)
    }

    /// The scene a snapshot is of, read without building anything: a caller can check
    /// it (its size, that it is the scene expected) before [`Simulation::restore_on`]
    /// allocates its particles.
    pub fn snapshot_scene(bytes: &[u8]) -> Result<Scene, SnapshotError> {
        Ok(Self::read_scene(bytes)?.0)
    }

    /// The scene of a snapshot, and the snapshot's parts.
    fn read_scene(bytes: &[u8]) -> Result<(Scene, snapshot::Parts), SnapshotError> {
        let bad = |m: String| SnapshotError::Malformed(m);
        let parts = snapshot::read(bytes)?;
        let value: serde_json::Value = serde_json::from_str(&parts.scene).map_err(|e| bad(format!("scene: {e}")))?;
        let scene = crate::scene::load::from_value(value).map_err(|e| bad(format!("scene: {e}")))?;
        Ok((scene, parts))
    }

    /// Rebuilds a scene from a snapshot, on the backend `make` builds.
    pub fn restore_on(bytes: &[u8], make: &BackendFactory) -> Result<Self, SnapshotError> {
        let bad = |m: String| SnapshotError::Malformed(m);
        let (scene, parts) = Self::read_scene(bytes)?;
        let mut sim = Self::new(scene, make).map_err(|e| bad(format!("scene: {e}")))?;
        let saved: SavedStats = serde_json::from_str(&parts.stats).map_err(|e| bad(format!("statistics: {e}")))?;
        sim.stats = RunStats { dt_sum: saved.dt_sum, compression_sum: saved.compression_sum, ..saved.stats };
        sim.halted = serde_json::from_str(&parts.halt).map_err(|e| bad(format!("halt: {e}")))?;
        sim.clock.restore(&parts.clock);
        snapshot::check_sections(sim.backend.model(), &parts.sections)?;
        if sim.backend.model().population.is_some() {
            // Checked: as many particles as ids, and the next id after them.
            let find = |name: &str| parts.sections.iter().find(|s| s.name == name).map(|s| s.column.clone());
            if let (Some(ids), Some(crate::attrs::Column::U32(next))) =
                (find("id"), find(crate::population::NEXT_ID.name))
            {
                sim.backend.set_particle_count(ids.len());
                sim.backend.model_mut().population.as_mut().expect("checked above").next_id = next[0];
            }
        }
        for s in parts.sections {
            sim.backend.upload(&s.name, s.column);
        }
        sim.backend.restored();
        Ok(sim)
    }

    fn record(&mut self, r: &StepReport) {
        let n = self.clock.steps() as f64;
        let s = &mut self.stats;
        let dt = r.dt as f64;
        if n == 1.0 {
            s.dt_min = dt;
            s.dt_max = dt;
        }
        s.dt_min = s.dt_min.min(dt);
        s.dt_max = s.dt_max.max(dt);
        s.dt_sum += dt;
        s.dt_mean = s.dt_sum / n;
        s.max_density_deviation = s.max_density_deviation.max(r.max_compression as f64);
        s.compression_sum += r.mean_compression as f64;
        s.mean_density_deviation = s.compression_sum / n;
        s.max_speed = s.max_speed.max(r.max_speed as f64);
        for solve in &r.solves {
            let e = s.solves.entry(solve.name.to_string()).or_default();
            e.total_iterations += u64::from(solve.iterations);
            e.max_iterations = e.max_iterations.max(solve.iterations);
            e.mean_iterations = e.total_iterations as f64 / n;
            e.last_residual = solve.residual;
        }
    }
}
