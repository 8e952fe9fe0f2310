//! What every backend (CPU now, GPU next) offers the rest of Floe.

use crate::guard::Halted;
use crate::quantize::PositionGrid;
use crate::stepping::{Clock, Passes, SortedState};
use serde::{Deserialize, Serialize};

/// A per-particle quantity a frame or export can carry besides position.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Channel {
    /// Velocity (m/s), 3 components.
    Velocity,
    /// Density (kg/m^3).
    Density,
    /// Pressure (Pa).
    Pressure,
}

impl Channel {
    /// Every channel of the fluid module.
    pub const FLUID: &'static [Channel] = &[Channel::Velocity, Channel::Density, Channel::Pressure];

    /// Name as used in exports (`density`) and components (`vx`, `vy`, `vz`).
    pub fn name(self) -> &'static str {
        match self {
            Channel::Velocity => "velocity",
            Channel::Density => "density",
            Channel::Pressure => "pressure",
        }
    }
}

/// A copy of particle state for output, in identity order (index = particle id).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Particles {
    /// Positions (m).
    pub positions: Vec<[f32; 3]>,
    /// Velocities (m/s), when asked for.
    pub velocities: Option<Vec<[f32; 3]>>,
    /// Densities (kg/m^3), when asked for.
    pub densities: Option<Vec<f32>>,
    /// Pressures (Pa), when asked for.
    pub pressures: Option<Vec<f32>>,
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Time step taken (s).
    pub dt: f32,
    /// Largest speed (m/s).
    pub max_speed: f32,
    /// Largest compression `(rho - rho0)/rho0`.
    pub max_compression: f32,
    /// Mean compression over particles (surface deficits count as 0).
    pub mean_compression: f32,
}

/// A simulation backend: owns the physics state and steps it.
///
/// A backend supplies its particle passes ([`Passes`]), its state and its
/// [`Clock`]; the step sequence, the clock's queries and snapshots are provided
/// here once for every backend.
pub trait Backend: Passes + Send {
    /// Short name (`cpu`, `gpu`).
    fn name(&self) -> &'static str;
    /// Where the run stands.
    fn clock(&self) -> &Clock;
    /// Where the run stands, to advance it.
    fn clock_mut(&mut self) -> &mut Clock;
    /// Number of fluid particles.
    fn particle_count(&self) -> usize;
    /// The particle state in sorted-slot order, for snapshots.
    fn sorted_state(&self) -> SortedState;
    /// Takes a state from a snapshot (then sorts and computes densities, so
    /// output is right at once).
    fn restore_state(&mut self, state: SortedState);

    /// Advances one step.
    fn step(&mut self) -> Result<StepReport, Halted> {
        let mut clock = self.clock().clone();
        let n = self.particle_count();
        let r = clock.step(self, n);
        *self.clock_mut() = clock;
        r
    }
    /// Simulated time (s).
    fn time(&self) -> f64 {
        self.clock().time()
    }
    /// Steps taken.
    fn steps(&self) -> u64 {
        self.clock().steps()
    }
    /// Steps taken beyond one per fixed interval (fixed time-step mode).
    fn substeps(&self) -> u64 {
        self.clock().substeps()
    }
    /// Mass of one fluid particle (kg).
    fn particle_mass(&self) -> f32 {
        self.model().fluid.mass
    }
    /// The simulation domain (m): particles leaving it halt the scene.
    fn domain(&self) -> crate::math::Aabb {
        self.model().domain
    }
    /// Writes the complete stepping state (see [`crate::snapshot`]).
    fn save(&self, out: &mut crate::snapshot::Writer) {
        self.clock().save(out, &self.sorted_state());
    }
    /// Loads a state written by [`Backend::save`] for the same scene.
    fn load(&mut self, r: &mut crate::snapshot::Reader<'_>) -> Result<(), crate::snapshot::SnapshotError> {
        let n = self.particle_count();
        let state = self.clock_mut().load(r, n)?;
        self.restore_state(state);
        Ok(())
    }
    /// Copies out positions and the requested channels.
    fn read(&self, channels: &[Channel]) -> Particles;
    /// Per pass or kernel: label, total seconds and calls so far. The CPU backend
    /// always reports wall time per pass; a GPU reports device time per kernel when
    /// asked to profile (`floe bench --profile`), and nothing otherwise.
    fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        Vec::new()
    }
    /// Bytes the scene holds in device memory (a GPU's buffers); `None` for a
    /// backend whose state lives in the process (see peak RSS instead).
    fn device_memory(&self) -> Option<u64> {
        None
    }
    /// Like [`Backend::read`], with positions that quantise on `grid` to the
    /// same codes as the exact ones: all a frame encoder quantising to `grid`
    /// needs. The exact positions qualify (this default, no extra work); a GPU
    /// quantises on the device, copies back 16-bit codes and returns their values.
    fn read_on_grid(&self, channels: &[Channel], _grid: &PositionGrid) -> Particles {
        self.read(channels)
    }
    /// Takes new tunable settings (see [`crate::scene::tunable`]) from `scene`.
    fn retune(&mut self, scene: &crate::scene::Scene);
}
