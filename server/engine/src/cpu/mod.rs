//! The CPU backend (rayon): the reference implementation every other backend is
//! tested against.
//!
//! State is structure-of-arrays in `f32`, re-sorted by grid cell at every
//! evaluation (see [`crate::neighbors`]); `ids` remembers each slot's particle
//! so output comes back in identity order.

mod passes;

use crate::backend::{Backend, Channel, Particles, StepReport};
use crate::guard::{Halted, Measures};
use crate::math::{Real, Vec3};
use crate::model::Model;
use crate::neighbors::{Grid, permute};
use crate::scene::Integrator;
use crate::snapshot::{Reader, SnapshotError, Writer};
use crate::timestep::{Limits, StepControl};
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
    control: StepControl,
    time: f64,
    steps: u64,
    /// Measures of the last evaluation; `None` until the first one.
    measures: Option<Measures>,
}

impl CpuBackend {
    /// Takes ownership of a model's initial state.
    pub fn new(mut model: Model) -> Self {
        let n = model.particle_count();
        let pos = std::mem::take(&mut model.positions);
        let vel = std::mem::take(&mut model.velocities);
        let grid = Grid::new(model.domain, model.kernel.support());
        let xsph = (model.fluid.xsph > 0.0).then(|| vec![Vec3::ZERO; n]);
        let control = StepControl::new(model.time_step);
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
            control,
            time: 0.0,
            steps: 0,
            measures: None,
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

    /// Sorts, then computes density, pressure, accelerations and measures.
    fn evaluate(&mut self) -> Result<Measures, Halted> {
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
        if let Some((reason, slot)) = m.violation(self.model.max_compression, self.model.max_speed) {
            return Err(self.halt(reason, Some(slot)));
        }
        self.measures = Some(m);
        Ok(m)
    }

    fn halt(&self, reason: String, slot: Option<u32>) -> Halted {
        Halted { step: self.steps, time: self.time, reason, particle: slot.map(|s| self.ids[s as usize]) }
    }

    fn dt(&mut self, m: &Measures) -> Result<Real, Halted> {
        let f = &self.model.fluid;
        let limits = Limits {
            h: 0.5 * self.model.kernel.support(),
            c: f.sound_speed,
            v_max: m.max_speed2.0.sqrt(),
            a_max: m.max_accel2.sqrt(),
            nu: f.viscosity.effective_nu(f.rho0),
        };
        self.control.next_dt(&limits).map_err(|reason| self.halt(reason, None))
    }

    /// `v += dt a` (plus the XSPH correction when `xsph`), with damping while it lasts.
    fn kick(&mut self, dt: Real, with_xsph: bool) {
        let (rate, until) = self.model.damping;
        let keep = if rate > 0.0 && self.time < until { (-rate * dt).exp() } else { 1.0 };
        let xsph = if with_xsph { self.xsph.as_deref() } else { None };
        self.vel.par_iter_mut().zip(self.acc.par_iter()).enumerate().with_min_len(4096).for_each(|(i, (v, &a))| {
            *v = (*v + a * dt) * keep + xsph.map_or(Vec3::ZERO, |x| x[i]);
        });
    }

    /// `x += dt v`, then the walls' non-penetration constraints.
    fn drift(&mut self, dt: Real) {
        let walls = &self.model.walls;
        self.pos.par_iter_mut().zip(self.vel.par_iter_mut()).with_min_len(4096).for_each(|(x, v)| {
            *x += *v * dt;
            for w in walls {
                w.apply(x, v);
            }
        });
    }

    fn report(&self, m: &Measures, dt: Real) -> StepReport {
        StepReport {
            dt,
            max_speed: m.max_speed2.0.sqrt(),
            max_compression: m.max_compression.0.max(0.0),
            mean_compression: (m.sum_compression / self.pos.len().max(1) as f64) as f32,
        }
    }
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn step(&mut self) -> Result<StepReport, Halted> {
        let (dt, m) = match self.model.integrator {
            Integrator::SymplecticEuler => {
                let m = self.evaluate()?;
                let dt = self.dt(&m)?;
                self.kick(dt, true);
                self.drift(dt);
                (dt, m)
            }
            Integrator::Leapfrog => {
                let m0 = match self.measures {
                    Some(m) => m,
                    None => self.evaluate()?,
                };
                let dt = self.dt(&m0)?;
                self.kick(0.5 * dt, false);
                self.drift(dt);
                let m = self.evaluate()?;
                self.kick(0.5 * dt, true);
                (dt, m)
            }
        };
        self.time += dt as f64;
        self.steps += 1;
        Ok(self.report(&m, dt))
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn steps(&self) -> u64 {
        self.steps
    }

    fn substeps(&self) -> u64 {
        self.control.substeps
    }

    fn particle_count(&self) -> usize {
        self.pos.len()
    }

    fn particle_mass(&self) -> f32 {
        self.model.fluid.mass
    }

    fn domain(&self) -> crate::math::Aabb {
        self.model.domain
    }

    fn retune(&mut self, scene: &crate::scene::Scene) {
        self.model.retune(scene);
        if self.model.time_step != *self.control.mode() {
            self.control = StepControl::new(self.model.time_step);
        }
        if self.model.fluid.xsph > 0.0 && self.xsph.is_none() {
            self.xsph = Some(vec![Vec3::ZERO; self.pos.len()]);
        } else if self.model.fluid.xsph == 0.0 {
            self.xsph = None;
        }
    }

    fn save(&self, out: &mut Writer) {
        out.f64(self.time);
        out.u64(self.steps);
        out.f32(self.control.remaining());
        out.u64(self.control.substeps);
        out.u64(self.pos.len() as u64);
        for v in [&self.pos, &self.vel, &self.acc] {
            out.f32s(v.iter().flat_map(|x| x.to_array()).collect::<Vec<_>>().into_iter());
        }
        out.f32s(self.ids.iter().map(|&i| f32::from_bits(i)).collect::<Vec<_>>().into_iter());
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

    fn load(&mut self, r: &mut Reader<'_>) -> Result<(), SnapshotError> {
        let time = r.f64("time")?;
        let steps = r.u64("steps")?;
        let (remaining, substeps) = (r.f32("time step control")?, r.u64("time step control")?);
        let n = r.u64("particle count")?;
        if n != self.pos.len() as u64 {
            return Err(SnapshotError::Malformed(format!("{n} particles, the scene has {}", self.pos.len())));
        }
        let n = n as usize;
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
        (self.time, self.steps, self.pos, self.vel, self.acc, self.ids, self.measures) =
            (time, steps, pos, vel, acc, ids, measures);
        self.control.restore(remaining, substeps);
        // Densities for output right away; the next step recomputes them identically.
        self.sort_and_density();
        Ok(())
    }

    fn read(&self, channels: &[Channel]) -> Particles {
        fn by_id<T: Copy + Default, U>(ids: &[u32], src: &[T], f: impl Fn(T) -> U) -> Vec<U>
        where
            U: Copy + Default,
        {
            let mut out = vec![U::default(); src.len()];
            for (&id, &v) in ids.iter().zip(src) {
                out[id as usize] = f(v);
            }
            out
        }
        let want = |c| channels.contains(&c);
        let eos = self.model.fluid.eos;
        Particles {
            positions: by_id(&self.ids, &self.pos, |v| v.to_array()),
            velocities: want(Channel::Velocity).then(|| by_id(&self.ids, &self.vel, |v| v.to_array())),
            densities: want(Channel::Density).then(|| by_id(&self.ids, &self.rho, |r| r)),
            pressures: want(Channel::Pressure).then(|| by_id(&self.ids, &self.rho, |r| eos.pressure(r))),
        }
    }
}
