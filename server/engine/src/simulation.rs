//! A scene being simulated: a backend plus the run's statistics and halt state.

use crate::backend::{Backend, Channel, Particles, StepReport};
use crate::cpu::CpuBackend;
use crate::guard::Halted;
use crate::model::{BuildError, Model};
use crate::scene::Scene;
use crate::snapshot::{MAGIC, Reader, SnapshotError, VERSION, Writer};
use serde::Serialize;

/// Statistics over every step taken so far.
#[derive(Debug, Clone, Default, Serialize)]
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
}

/// A running scene.
pub struct Simulation {
    scene: Scene,
    backend: Box<dyn Backend>,
    stats: RunStats,
    dt_sum: f64,
    compression_sum: f64,
    halted: Option<Halted>,
}

impl std::fmt::Debug for Simulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("scene", &self.scene.name)
            .field("backend", &self.backend.name())
            .field("time", &self.backend.time())
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
        Self { scene, backend, stats: RunStats::default(), dt_sum: 0.0, compression_sum: 0.0, halted: None }
    }

    /// The scene as given.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The backend's name.
    pub fn backend_name(&self) -> &'static str {
        self.backend.name()
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.backend.time()
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.backend.steps()
    }

    /// Sub-steps taken by fixed time-step mode.
    pub fn substeps(&self) -> u64 {
        self.backend.substeps()
    }

    /// Number of fluid particles.
    pub fn particle_count(&self) -> usize {
        self.backend.particle_count()
    }

    /// Mass of one fluid particle (kg).
    pub fn particle_mass(&self) -> f32 {
        self.backend.particle_mass()
    }

    /// The simulation domain (m).
    pub fn domain(&self) -> crate::math::Aabb {
        self.backend.domain()
    }

    /// Why the scene stopped, if it did.
    pub fn halted(&self) -> Option<&Halted> {
        self.halted.as_ref()
    }

    /// Run statistics so far.
    pub fn stats(&self) -> &RunStats {
        &self.stats
    }

    /// Copies out positions and the requested channels, in identity order.
    pub fn read(&self, channels: &[Channel]) -> Particles {
        self.backend.read(channels)
    }

    /// Per-kernel device time (see [`Backend::kernel_times`]).
    pub fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.backend.kernel_times()
    }

    /// Bytes held in device memory (see [`Backend::device_memory`]).
    pub fn device_memory(&self) -> Option<u64> {
        self.backend.device_memory()
    }

    /// [`Simulation::read`] with positions on `grid` (see [`Backend::read_on_grid`]).
    pub fn read_on_grid(&self, channels: &[Channel], grid: &crate::quantize::PositionGrid) -> Particles {
        self.backend.read_on_grid(channels, grid)
    }

    /// One step. After a halt every call returns the same [`Halted`].
    pub fn step(&mut self) -> Result<StepReport, Halted> {
        if let Some(h) = &self.halted {
            return Err(h.clone());
        }
        match self.backend.step() {
            Ok(r) => {
                self.record(&r);
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
        self.scene = next;
        Ok(())
    }

    /// The complete state as bytes (see [`crate::snapshot`]).
    pub fn snapshot(&self) -> Vec<u8> {
        let mut w = Writer(Vec::new());
        w.0.extend_from_slice(MAGIC);
        w.u32(VERSION);
        w.bytes(serde_json::to_string(&self.scene).expect("scenes serialise").as_bytes());
        let s = &self.stats;
        for v in [s.dt_min, s.dt_mean, s.dt_max, s.max_density_deviation, s.mean_density_deviation, s.max_speed] {
            w.f64(v);
        }
        w.f64(self.dt_sum);
        w.f64(self.compression_sum);
        w.bytes(serde_json::to_string(&self.halted).expect("halts serialise").as_bytes());
        self.backend.save(&mut w);
        w.0
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

    /// The scene of a snapshot, and a reader at what follows it.
    fn read_scene(bytes: &[u8]) -> Result<(Scene, Reader<'_>), SnapshotError> {
        let bad = |m: String| SnapshotError::Malformed(m);
        if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
            return Err(bad("it does not start with FLOESNAP".into()));
        }
        let mut r = Reader::new(&bytes[MAGIC.len()..]);
        let version = r.u32("version")?;
        if version != VERSION {
            return Err(SnapshotError::UnsupportedVersion(version));
        }
        let scene_json = r.bytes("scene")?;
        let value: serde_json::Value = serde_json::from_slice(scene_json).map_err(|e| bad(format!("scene: {e}")))?;
        let scene = crate::scene::load::from_value(value).map_err(|e| bad(format!("scene: {e}")))?;
        Ok((scene, r))
    }

    /// Rebuilds a scene from a snapshot, on the backend `make` builds.
    pub fn restore_on(bytes: &[u8], make: &BackendFactory) -> Result<Self, SnapshotError> {
        let bad = |m: String| SnapshotError::Malformed(m);
        let (scene, mut r) = Self::read_scene(bytes)?;
        let mut sim = Self::new(scene, make).map_err(|e| bad(format!("scene: {e}")))?;
        let mut f = [0.0; 6];
        for v in &mut f {
            *v = r.f64("statistics")?;
        }
        sim.stats = RunStats {
            dt_min: f[0],
            dt_mean: f[1],
            dt_max: f[2],
            max_density_deviation: f[3],
            mean_density_deviation: f[4],
            max_speed: f[5],
        };
        sim.dt_sum = r.f64("statistics")?;
        sim.compression_sum = r.f64("statistics")?;
        sim.halted = serde_json::from_slice(r.bytes("halt")?).map_err(|e| bad(format!("halt: {e}")))?;
        sim.backend.load(&mut r)?;
        r.finish()?;
        Ok(sim)
    }

    fn record(&mut self, r: &StepReport) {
        let n = self.backend.steps() as f64;
        let s = &mut self.stats;
        let dt = r.dt as f64;
        if n == 1.0 {
            s.dt_min = dt;
            s.dt_max = dt;
        }
        s.dt_min = s.dt_min.min(dt);
        s.dt_max = s.dt_max.max(dt);
        self.dt_sum += dt;
        s.dt_mean = self.dt_sum / n;
        s.max_density_deviation = s.max_density_deviation.max(r.max_compression as f64);
        self.compression_sum += r.mean_compression as f64;
        s.mean_density_deviation = self.compression_sum / n;
        s.max_speed = s.max_speed.max(r.max_speed as f64);
    }
}
