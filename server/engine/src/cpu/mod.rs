//! The CPU backend (rayon): the reference implementation every other backend is
//! tested against.
//!
//! It holds a scene's attributes in an [`Attrs`] store (structure of arrays, `f32`)
//! and runs the passes of the scene's plan: each pass's CPU implementation
//! ([`CpuPass`]) is looked up by name once, from the core, the scheme and the
//! modules. The particle space is re-sorted by grid cell at every evaluation
//! ([`crate::neighbors`]); `id` remembers each slot's particle so output comes back
//! in identity order.
//!
//! - [`core`]: the core's passes (sort, density), the reduction, kick and drift.
//! - [`neighbors`]: the step's neighbour lists.

pub mod core;
pub mod neighbors;

use crate::attrs::{Allocation, Attrs, Column};
use crate::backend::Backend;
use crate::guard::Measures;
use crate::math::Real;
use crate::model::Model;
use crate::neighbors::Grid;
use crate::plan::{PassSpec, Stage};
use crate::scheme::{ReduceOp, Reduction, Stages};
use neighbors::NeighborLists;

/// What a CPU pass works on.
#[derive(Debug)]
pub struct CpuCx<'a> {
    /// The model (constants, materials, walls).
    pub model: &'a Model,
    /// Every attribute.
    pub attrs: &'a mut Attrs,
    /// The particle grid after the last sort.
    pub grid: &'a mut Grid,
    /// The step's neighbour lists (filled by the density pass).
    pub nb: &'a mut NeighborLists,
    /// The sort's scratch space.
    pub sort: &'a mut SortScratch,
    /// The step's dt (s), for passes that integrate.
    pub dt: Real,
    /// The sweep of the iteration running (see [`crate::scheme::Iterate::sweeps`]).
    pub sweep: u32,
}

/// Scratch space of the counting sort.
#[derive(Debug, Default)]
pub struct SortScratch {
    /// Cell of each particle.
    pub cells: Vec<u32>,
    /// The permutation.
    pub order: Vec<u32>,
}

/// A pass's CPU implementation.
pub trait CpuPass: Send + Sync + std::fmt::Debug {
    /// Runs the pass.
    fn run(&self, cx: &mut CpuCx<'_>);
}

/// Every CPU pass implementation of the core, the schemes and the modules, by name.
fn all() -> Vec<(&'static str, &'static dyn CpuPass)> {
    let modules = crate::module::all();
    let schemes = crate::scheme::all();
    let lists = core::PASSES
        .iter()
        .chain(crate::viscosity::CPU)
        .chain(crate::position_solve::CPU)
        .chain(schemes.iter().flat_map(|s| s.cpu))
        .chain(modules.iter().flat_map(|m| m.cpu));
    lists.copied().collect()
}

fn implementation(name: &str) -> Option<&'static dyn CpuPass> {
    all().into_iter().find(|(n, _)| *n == name).map(|(_, p)| p)
}

/// The names of every pass the CPU implements (the GPU's list must match).
pub fn implementations() -> Vec<&'static str> {
    all().into_iter().map(|(n, _)| n).collect()
}

/// A scene's state and scratch space on the CPU.
#[derive(Debug)]
pub struct CpuBackend {
    model: Model,
    attrs: Attrs,
    grid: Grid,
    nb: NeighborLists,
    sort: SortScratch,
    /// The plan's passes with their implementations, in plan order.
    passes: Vec<(&'static PassSpec, &'static dyn CpuPass)>,
    /// Every plan pass run so far, in the order first run ([`Backend::passes_run`]).
    ran: Vec<&'static str>,
    /// Wall time (s) and calls of every pass, kick and drift so far
    /// ([`Backend::kernel_times`]).
    times: Vec<(&'static str, f64, u64)>,
    /// The sweep index passes see ([`Stages::sweep`]).
    sweep: u32,
}

impl CpuBackend {
    /// Takes ownership of a model's initial state.
    pub fn new(mut model: Model) -> Self {
        let mut attrs = Attrs::new(model.layout.take_columns());
        // Room for every particle the scene may hold, so births allocate nothing.
        let (n, capacity) = (model.particle_count(), model.particle_capacity());
        attrs.resize(crate::attrs::PARTICLES, n, capacity);
        let grid = Grid::new(model.domain, model.kernel.support(), model.periodic.axes);
        let passes = Self::resolve(&model);
        Self {
            model,
            attrs,
            grid,
            nb: NeighborLists::default(),
            sort: SortScratch::default(),
            passes,
            ran: Vec::new(),
            times: Vec::new(),
            sweep: 0,
        }
    }

    fn resolve(model: &Model) -> Vec<(&'static PassSpec, &'static dyn CpuPass)> {
        let imp = |p: &'static PassSpec| {
            implementation(p.name).unwrap_or_else(|| panic!("pass {} has no CPU implementation", p.name))
        };
        model.plan.passes().iter().map(|&p| (p, imp(p))).collect()
    }

    fn run_one(&mut self, pass: &'static PassSpec, imp: &'static dyn CpuPass, dt: Real) {
        if !self.ran.contains(&pass.name) {
            self.ran.push(pass.name);
        }
        let t0 = std::time::Instant::now();
        let mut cx = CpuCx {
            model: &self.model,
            attrs: &mut self.attrs,
            grid: &mut self.grid,
            nb: &mut self.nb,
            sort: &mut self.sort,
            dt,
            sweep: self.sweep,
        };
        cx.attrs.view(Some(pass));
        imp.run(&mut cx);
        cx.attrs.view(None);
        record(&mut self.times, pass.name, t0);
    }
}

/// Adds the wall time since `t0` to pass `name` of `times`.
fn record(times: &mut Vec<(&'static str, f64, u64)>, name: &'static str, t0: std::time::Instant) {
    let seconds = t0.elapsed().as_secs_f64();
    match times.iter_mut().find(|e| e.0 == name) {
        Some(e) => (e.1, e.2) = (e.1 + seconds, e.2 + 1),
        None => times.push((name, seconds, 1)),
    }
}

impl Stages for CpuBackend {
    fn model(&self) -> &Model {
        &self.model
    }

    fn run(&mut self, stage: Stage, dt: Real) {
        for i in 0..self.passes.len() {
            let (p, imp) = self.passes[i];
            if p.stage == stage {
                self.run_one(p, imp, dt);
            }
        }
    }

    fn run_pass(&mut self, name: &str, dt: Real) {
        let (p, imp) = *self.passes.iter().find(|(p, _)| p.name == name).unwrap_or_else(|| panic!("no pass {name}"));
        self.run_one(p, imp, dt);
    }

    fn measure(&mut self) -> Result<Measures, String> {
        Ok(core::measure(&self.model, &self.attrs))
    }

    fn reduce(&mut self, r: &Reduction) -> Result<f64, String> {
        let values = self.attrs.get(self.attrs.handle::<Real>(r.attr));
        let n = values.len().max(1) as f64;
        let sum = || values.iter().map(|&v| f64::from(v)).sum::<f64>();
        Ok(match r.op {
            ReduceOp::Sum => sum(),
            ReduceOp::Mean => sum() / n,
            ReduceOp::Norm => sum().sqrt(),
            ReduceOp::Max => values.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(f64::from(v))),
            ReduceOp::MaxAbs => values.iter().fold(0.0, |m: f64, &v| m.max(f64::from(v.abs()))),
            ReduceOp::Outside { min, max } => values.iter().filter(|&&v| !(min..=max).contains(&v)).count() as f64,
        })
    }

    fn sum_into(&mut self, attr: &'static str, into: &'static str, slot: u32) {
        let t0 = std::time::Instant::now();
        let sum = self.reduce(&Reduction { attr, op: ReduceOp::Sum }).expect("the CPU sums any attribute");
        let h = self.attrs.handle::<Real>(into);
        let mut scalars = self.attrs.take(h);
        scalars[slot as usize] = sum as Real;
        self.attrs.put(h, scalars);
        record(&mut self.times, "sum", t0);
    }

    fn kick(&mut self, dt: Real, keep: Real) {
        let t0 = std::time::Instant::now();
        core::kick(&mut self.attrs, dt, keep);
        record(&mut self.times, "kick", t0);
    }

    fn drift(&mut self, dt: Real) {
        let t0 = std::time::Instant::now();
        core::drift(&self.model, &mut self.attrs, dt);
        record(&mut self.times, "drift", t0);
    }

    fn sweep(&mut self, k: u32) {
        self.sweep = k;
    }

    fn particle_id(&mut self, slot: u32) -> u32 {
        self.attrs.get(self.attrs.handle::<u32>("id"))[slot as usize]
    }

    fn first_outside(&mut self, attr: &str, min: Real, max: Real) -> Option<(u32, Real)> {
        crate::guard::first_outside(self.attrs.get(self.attrs.handle::<Real>(attr)), min, max)
    }
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn download(&self, names: &[&str]) -> Vec<Column> {
        names.iter().map(|n| self.attrs.column(n).unwrap_or_else(|| panic!("no attribute {n}")).clone()).collect()
    }

    fn upload(&mut self, name: &str, column: Column) {
        self.attrs.set_column(name, column);
    }

    fn restored(&mut self) {
        // Densities (and anything else derived) for output right away; the next step
        // recomputes them identically.
        self.run(Stage::Sort, 0.0);
        self.run(Stage::Density, 0.0);
    }

    fn retuned(&mut self) {
        // Attributes that came or went with a setting (XSPH), then the passes.
        let wanted: Vec<_> = self.model.layout.specs().collect();
        if wanted.iter().map(|s| s.name).ne(self.attrs.specs().iter().map(|s| s.name)) {
            let mut old = std::mem::take(&mut self.attrs).into_columns();
            let columns = wanted
                .into_iter()
                .map(|spec| match old.iter().position(|(s, _)| s.name == spec.name) {
                    Some(i) => old.swap_remove(i),
                    None => (spec, Column::zeros(spec.elem, self.model.layout.count(spec.space))),
                })
                .collect();
            self.attrs = Attrs::new(columns);
            let (n, capacity) = (self.model.particle_count(), self.model.particle_capacity());
            self.attrs.resize(crate::attrs::PARTICLES, n, capacity);
        }
        self.passes = Self::resolve(&self.model);
    }

    fn model_mut(&mut self) -> &mut Model {
        &mut self.model
    }

    /// Each column's room (the particle attributes' holds the scene's capacity).
    fn allocations(&self) -> Vec<Allocation> {
        self.attrs.allocations()
    }

    fn compact(&mut self) {
        let remove = self.attrs.get(self.attrs.handle::<Real>(crate::population::REMOVE.name));
        if remove.iter().all(|&r| r == 0.0) {
            return;
        }
        let keep: Vec<bool> = remove.iter().map(|&r| r == 0.0).collect();
        self.attrs.retain(crate::attrs::PARTICLES, &keep);
        self.model.set_particle_count(keep.iter().filter(|&&k| k).count());
    }

    fn emit(&mut self, births: &crate::population::Births, first_id: u32) {
        let n = self.model.particle_count();
        let total = n + births.len();
        self.set_particle_count(total);
        let a = &mut self.attrs;
        let (x, v, id) =
            (a.handle::<crate::math::Vec3>("x"), a.handle::<crate::math::Vec3>("v"), a.handle::<u32>("id"));
        a.get_mut(x)[n..].copy_from_slice(&births.x);
        a.get_mut(v)[n..].copy_from_slice(&births.v);
        a.get_mut(id)[n..].iter_mut().zip(first_id..).for_each(|(i, next)| *i = next);
        if let Some(m) = a.find::<u32>("material") {
            a.get_mut(m)[n..].copy_from_slice(&births.material);
        }
    }

    fn set_particle_count(&mut self, n: usize) {
        self.attrs.resize(crate::attrs::PARTICLES, n, self.model.particle_capacity());
        self.model.set_particle_count(n);
    }

    fn passes_run(&self) -> Vec<&'static str> {
        self.ran.clone()
    }

    /// Wall time per pass, kick and drift (always measured: two clock reads each).
    fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.times.clone()
    }
}
