//! The CPU backend (rayon): the reference implementation every other backend is
//! tested against.
//!
//! State is structure-of-arrays in `f32`, re-sorted by grid cell at every
//! evaluation (see [`crate::neighbors`]); `ids` remembers each slot's particle
//! so output comes back in identity order.

mod passes;

use crate::backend::{Backend, Channel, Particles};
use crate::guard::Measures;
use crate::math::{Real, Vec3};
use crate::model::Model;
use crate::neighbors::{Grid, permute};
use crate::stepping::{Clock, Passes, SortedState, by_identity};
use rayon::prelude::*;

/// Fluid state and scratch buffers on the CPU.
#[derive(Debug)]
pub struct CpuBackend {
    model: Model,
    pos: Vec<Vec3>,
    vel: Vec<Vec3>,
    acc: Vec<Vec3>,
    rho: Vec<Real>,
    pterm: Vec<Real>,
    /// Pressure of each wall particle (Pa), extrapolated from the fluid.
    wall_p: Vec<Real>,
    ids: Vec<u32>,
    /// XSPH corrections; allocated only when the fluid uses XSPH.
    xsph: Option<Vec<Vec3>>,
    grid: Grid,
    /// Neighbour lists of the current step, per chunk of particles.
    neighbors: Vec<passes::ChunkNeighbors>,
    cells: Vec<u32>,
    order: Vec<u32>,
    scratch_v: Vec<Vec3>,
    scratch_u: Vec<u32>,
    clock: Clock,
    /// Wall time per pass (label, seconds, calls): `Backend::kernel_times`.
    times: Vec<(&'static str, f64, u64)>,
}

/// Adds the wall time since `t0` to pass `label` of `times`.
fn record(times: &mut Vec<(&'static str, f64, u64)>, label: &'static str, t0: std::time::Instant) {
    let seconds = t0.elapsed().as_secs_f64();
    match times.iter_mut().find(|e| e.0 == label) {
        Some(e) => (e.1, e.2) = (e.1 + seconds, e.2 + 1),
        None => times.push((label, seconds, 1)),
    }
}

impl CpuBackend {
    /// Takes ownership of a model's initial state.
    pub fn new(mut model: Model) -> Self {
        let n = model.particle_count();
        let pos = std::mem::take(&mut model.positions);
        let vel = std::mem::take(&mut model.velocities);
        let grid = Grid::new(model.domain, model.kernel.support());
        let xsph = (model.fluid.xsph > 0.0).then(|| vec![Vec3::ZERO; n]);
        let clock = Clock::new(&model);
        let walls = model.boundary.len();
        Self {
            model,
            pos,
            vel,
            acc: vec![Vec3::ZERO; n],
            rho: vec![0.0; n],
            pterm: vec![0.0; n],
            wall_p: vec![0.0; walls],
            ids: (0..n as u32).collect(),
            xsph,
            grid,
            neighbors: Vec::new(),
            cells: Vec::new(),
            order: Vec::new(),
            scratch_v: Vec::new(),
            scratch_u: Vec::new(),
            clock,
            times: Vec::new(),
        }
    }

    /// Sorts by cell (a stable sort: sorting sorted particles changes nothing) and
    /// computes density and pressure.
    fn sort_and_density(&mut self) {
        self.grid.sort(&self.pos, &mut self.cells, &mut self.order);
        permute(&mut self.pos, &mut self.scratch_v, &self.order);
        permute(&mut self.vel, &mut self.scratch_v, &self.order);
        permute(&mut self.acc, &mut self.scratch_v, &self.order);
        permute(&mut self.ids, &mut self.scratch_u, &self.order);
        passes::density(&self.model, &self.grid, &self.pos, &mut self.neighbors, &mut self.rho, &mut self.pterm);
    }
}

impl Passes for CpuBackend {
    fn model(&self) -> &Model {
        &self.model
    }

    fn evaluate(&mut self) -> Result<Measures, String> {
        let t0 = std::time::Instant::now();
        self.sort_and_density();
        passes::wall_pressure(&self.model, &self.grid, &self.pos, &self.rho, &self.pterm, &mut self.wall_p);
        passes::forces(
            &self.model,
            &self.neighbors,
            &self.pos,
            &self.vel,
            &self.rho,
            &self.pterm,
            &self.wall_p,
            &mut self.acc,
            self.xsph.as_deref_mut(),
        );
        let m = passes::measure(&self.pos, &self.vel, &self.acc, &self.rho, self.model.fluid.rho0, self.model.domain);
        record(&mut self.times, "evaluate", t0);
        Ok(m)
    }

    fn kick(&mut self, dt: Real, keep: Real, with_xsph: bool) {
        let t0 = std::time::Instant::now();
        let xsph = if with_xsph { self.xsph.as_deref() } else { None };
        self.vel.par_iter_mut().zip(self.acc.par_iter()).enumerate().with_min_len(4096).for_each(|(i, (v, &a))| {
            *v = (*v + a * dt) * keep + xsph.map_or(Vec3::ZERO, |x| x[i]);
        });
        record(&mut self.times, "kick", t0);
    }

    fn drift(&mut self, dt: Real) {
        let t0 = std::time::Instant::now();
        let walls = &self.model.walls;
        self.pos.par_iter_mut().zip(self.vel.par_iter_mut()).with_min_len(4096).for_each(|(x, v)| {
            *x += *v * dt;
            for w in walls {
                w.apply(x, v);
            }
        });
        record(&mut self.times, "drift", t0);
    }

    fn particle_id(&mut self, slot: u32) -> u32 {
        self.ids[slot as usize]
    }
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn clock(&self) -> &Clock {
        &self.clock
    }

    fn clock_mut(&mut self) -> &mut Clock {
        &mut self.clock
    }

    fn particle_count(&self) -> usize {
        self.pos.len()
    }

    fn retune(&mut self, scene: &crate::scene::Scene) {
        self.model.retune(scene);
        self.clock.retune(&self.model);
        if self.model.fluid.xsph > 0.0 && self.xsph.is_none() {
            self.xsph = Some(vec![Vec3::ZERO; self.pos.len()]);
        } else if self.model.fluid.xsph == 0.0 {
            self.xsph = None;
        }
    }

    fn sorted_state(&self) -> SortedState {
        SortedState { pos: self.pos.clone(), vel: self.vel.clone(), acc: self.acc.clone(), ids: self.ids.clone() }
    }

    fn restore_state(&mut self, s: SortedState) {
        (self.pos, self.vel, self.acc, self.ids) = (s.pos, s.vel, s.acc, s.ids);
        // Densities for output right away; the next step recomputes them identically.
        self.sort_and_density();
    }

    fn read(&self, channels: &[Channel]) -> Particles {
        by_identity(channels, &self.ids, &self.pos, Some(&self.vel), Some(&self.rho), &self.model.fluid.eos)
    }

    /// Wall time per pass of the step sequence (always measured: a few clock reads per step).
    fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.times.clone()
    }
}
