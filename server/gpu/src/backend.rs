//! [`GpuBackend`]: the engine's [`Backend`] with every pass of the plan on the GPU.
//!
//! A scheme's stages are recorded into one command buffer per evaluation; the
//! backend waits only for the 32-byte measures the time step and guard need (and,
//! for an iterative solve, a 4-byte residual per check). Kicks and drifts are
//! submitted without waiting. Each plan pass is bound by name ([`crate::pass`]), so
//! this file knows no module. [`readback`] copies results back to the CPU;
//! [`population`] removes and adds particles.

mod binds;
mod population;
mod readback;

use binds::{CoreBinds, PlanPass, core_binds, plan_passes};

use crate::buffers::{Buffers, PACKED, STEP_SLOTS, from_gpu_words, gpu_words};
use crate::context::GpuContext;
use crate::layout::{Measures, Params, Step, Words};
use crate::passes::PER_PARTIAL;
use crate::program::Recorder;
use crate::timer::Timer;
use floe_engine::attrs::{Allocation, Column, PARTICLES, WALLS};
use floe_engine::backend::{Backend, Particles};
use floe_engine::channels::SetSpec;
use floe_engine::math::Real;
use floe_engine::model::{BuildError, Model};
use floe_engine::neighbors::Grid;
use floe_engine::plan::Stage;
use floe_engine::quantize::PositionGrid;
use floe_engine::scheme::{ReduceOp, Reduction, Stages};
use wgpu::{BindGroup, Buffer};

/// One scene on the GPU.
#[derive(Debug)]
pub struct GpuBackend {
    gpu: GpuContext,
    model: Model,
    grid: Grid,
    n: u32,
    buffers: Buffers,
    core: CoreBinds,
    passes: Vec<PlanPass>,
    /// Reduction bind groups, by attribute.
    reductions: Vec<(&'static str, BindGroup)>,
    /// Kicks and drifts recorded since the last submission.
    pending: Option<Recorder>,
    /// Per-kernel GPU time, when profiling (held by `pending` while recording).
    timer: Option<Timer>,
    /// Next free step uniform of `buffers.steps`.
    slot: usize,
    /// Every pass recorded so far, in the order first recorded.
    ran: Vec<&'static str>,
    /// The dt in the `dt` uniform (NaN before the first write).
    pass_dt: Real,
    /// Whether drifts add `dt/2 a_transport` (1) or not (0): the scene has the attribute.
    transport: u32,
}

impl GpuBackend {
    /// Uploads `model`'s initial state to the GPU of `gpu`.
    pub fn new(gpu: &GpuContext, mut model: Model) -> Result<Self, BuildError> {
        let grid = Grid::new(model.domain, model.kernel.support(), model.periodic.axes);
        // Every pass of the plan needs a GPU kernel, or the scene is refused by name.
        for p in model.plan.passes() {
            if !crate::pass::HOST_PASSES.contains(&p.name) && crate::pass::find(p.name, &model).is_none() {
                return Err(BuildError::Backend(format!(
                    "pass {} (module {}) has no GPU implementation; run this scene on the CPU backend",
                    p.name, p.module
                )));
            }
        }
        // A scene too large for the device's memory is refused, not a panic.
        let oom = gpu.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let invalid = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let buffers = Buffers::new(gpu, &mut model, &grid)?;
        let n = model.particle_count() as u32;
        let core = core_binds(gpu, &buffers, &grid);
        let passes = plan_passes(gpu, &model, &buffers);
        let refused = pollster::block_on(invalid.pop()).or(pollster::block_on(oom.pop()));
        if let Some(e) = refused {
            return Err(BuildError::Backend(format!("the GPU cannot hold this scene: {e}")));
        }
        let transport = u32::from(buffers.find("a_transport").is_some());
        let timer = gpu.profiling().then(|| Timer::new(&gpu.device, gpu.queue.get_timestamp_period()));
        Ok(Self {
            gpu: gpu.clone(),
            model,
            grid,
            n,
            buffers,
            core,
            passes,
            reductions: Vec::new(),
            pending: None,
            timer,
            slot: 0,
            ran: Vec::new(),
            pass_dt: Real::NAN,
            transport,
        })
    }

    /// The recorder being filled (taken out; put it back in `pending` or submit it).
    fn take_recorder(&mut self) -> Recorder {
        self.pending.take().unwrap_or_else(|| Recorder {
            encoder: self
                .gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("floe step") }),
            timer: self.timer.take(),
        })
    }

    /// Submits `rec` without waiting (when profiling, waits for its timestamps).
    fn submit(&mut self, rec: Recorder) {
        let Recorder { mut encoder, mut timer } = rec;
        let stamps = timer.as_ref().and_then(|t| t.resolve(&mut encoder)).map(|(b, len)| (b.clone(), len));
        self.gpu.queue.submit([encoder.finish()]);
        self.slot = 0;
        if let (Some(t), Some((buffer, len))) = (timer.as_mut(), stamps) {
            t.add(&self.download_words(&[(&buffer, 0, len)])[0]);
        }
        self.timer = timer;
    }

    /// Submits the kicks and drifts recorded so far, without waiting.
    pub fn flush(&mut self) {
        if let Some(rec) = self.pending.take() {
            self.submit(rec);
        }
        self.slot = 0;
    }

    /// Records the stable counting sort by cell and the permutation of every state
    /// attribute of the particle space (through the scratch buffer), then the slot
    /// of each id.
    fn record_sort(&mut self, e: &mut Recorder) {
        let (n, cells) = (self.n, self.grid.cell_count() as u32);
        let p = &self.gpu.programs;
        let (b, c) = (&self.buffers, &self.core);
        e.encoder.clear_buffer(b.get("starts"), 0, Some(4 * (cells as u64 + 1)));
        p.grid_count.dispatch(e, &c.grid, n);
        p.scan.record(e, &c.scan);
        p.grid_scatter.dispatch(e, &c.grid, n);
        p.grid_settle.dispatch(e, &c.grid, cells);
        let scratch = b.get("sort_scratch");
        for (name, words, bind) in &c.permutes {
            p.permute.dispatch(e, bind, n * words);
            e.encoder.copy_buffer_to_buffer(scratch, 0, b.get(name), 0, 4 * (n * words) as u64);
        }
        if let Some(slots) = &c.slots {
            p.slots.dispatch(e, slots, n);
        }
    }

    /// Records plan pass `i` with its own kernel, or with `fused` its fused kernel
    /// (which does the passes it covers too).
    fn record_pass(&mut self, i: usize, dt: Real, fused: bool) {
        if self.passes[i].uses_dt && dt.to_bits() != self.pass_dt.to_bits() {
            // Work recorded so far reads the old dt: it goes first. The other three
            // components stay 0 (heat's integrate.wgsl XORs with the bits of w).
            self.flush();
            self.gpu.queue.write_buffer(self.buffers.get("dt"), 0, bytemuck::bytes_of(&[dt, 0.0, 0.0, 0.0]));
            self.pass_dt = dt;
        }
        let mut e = self.take_recorder();
        let pass = &self.passes[i];
        let done: Vec<usize> = match (&pass.fused, fused) {
            (Some((_, _, covers)), true) => covers.clone(),
            _ => vec![i],
        };
        for k in done {
            if !self.ran.contains(&self.passes[k].spec.name) {
                self.ran.push(self.passes[k].spec.name);
            }
        }
        let pass = &self.passes[i];
        match (&pass.fused, &pass.kernel) {
            (Some((kernel, bind, _)), _) if fused => kernel.dispatch(&mut e, bind, pass.threads),
            (_, Some((kernel, bind))) => kernel.dispatch(&mut e, bind, pass.threads),
            (_, None) if pass.spec.name == "core.sort" => self.record_sort(&mut e),
            (_, None) => {}
        }
        self.pending = Some(e);
    }

    fn write_step(&mut self, step: Step) -> usize {
        let slot = self.slot;
        assert!(slot < STEP_SLOTS, "more kicks and drifts between two evaluations than step slots");
        self.slot += 1;
        self.gpu.queue.write_buffer(&self.buffers.steps[slot], 0, bytemuck::bytes_of(&step));
        slot
    }

    /// Takes `n` live particles (births and deaths, a restore): the count in the
    /// model, the scene constants, the permutations' and the passes' thread counts.
    fn resized(&mut self, n: u32) {
        self.flush();
        self.n = n;
        self.model.set_particle_count(n as usize);
        let (gpu, b) = (&self.gpu, &self.buffers);
        gpu.queue.write_buffer(b.get("params"), 0, bytemuck::bytes_of(&Params::new(&self.model, &self.grid)));
        for (stride, buffer) in &b.strides {
            gpu.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&Words { n, stride: *stride, ..Words::default() }));
        }
        for p in &mut self.passes {
            let space =
                p.kernel.as_ref().and(crate::pass::find(p.spec.name, &self.model)).map_or(PARTICLES, |k| k.space);
            if space == PARTICLES {
                p.threads = n;
            }
        }
    }

    /// Elements of `space`.
    fn count(&self, space: &str) -> u64 {
        self.model.layout.count(space) as u64
    }

    /// Records the reduction of attribute `attr` with operation code `op` (reduce.wgsl)
    /// after what is pending; its total lands in `reduce_partials[0]`. Returns the
    /// recorder (not submitted) and the count of values reduced.
    fn record_reduction(&mut self, attr: &str, op: u32, lo: Real, hi: Real) -> Result<(Recorder, u32), String> {
        let spec = self.model.layout.spec(attr).ok_or_else(|| format!("no attribute {attr}"))?;
        let n = self.count(spec.space) as u32;
        let words = Words { n, stride: 1, op, lo, hi, ..Words::default() };
        self.gpu.queue.write_buffer(self.buffers.get("reduce_words"), 0, bytemuck::bytes_of(&words));
        let bind = self.reduction(spec.name).clone();
        let mut e = self.take_recorder();
        let p = &self.gpu.programs;
        p.reduce_partials.dispatch(&mut e, &bind, n);
        p.reduce_total.dispatch(&mut e, &bind, PER_PARTIAL);
        Ok((e, n))
    }

    /// The reduction bind group of attribute `attr`, made on first use.
    fn reduction(&mut self, attr: &'static str) -> &BindGroup {
        if !self.reductions.iter().any(|(a, _)| *a == attr) {
            let b = &self.buffers;
            let bind = self
                .gpu
                .programs
                .reduce_partials
                .bind(&self.gpu.device, &[b.get("reduce_words"), b.get(attr), b.get("reduce_partials")]);
            self.reductions.push((attr, bind));
        }
        &self.reductions.iter().find(|(a, _)| *a == attr).expect("made above").1
    }
}

impl Stages for GpuBackend {
    fn model(&self) -> &Model {
        &self.model
    }

    /// The stage's passes in plan order, those a fused kernel does with it.
    fn run(&mut self, stage: Stage, dt: Real) {
        let mut done: Vec<usize> = Vec::new();
        for i in 0..self.passes.len() {
            if self.passes[i].spec.stage == stage && !done.contains(&i) {
                if let Some((_, _, covers)) = &self.passes[i].fused {
                    done.extend(covers);
                }
                self.record_pass(i, dt, true);
            }
        }
    }

    /// One pass with its own kernel, never fused (the oracle compares passes so).
    fn run_pass(&mut self, name: &str, dt: Real) {
        let i = self.passes.iter().position(|p| p.spec.name == name).unwrap_or_else(|| panic!("no pass {name}"));
        self.record_pass(i, dt, false);
    }

    fn measure(&mut self) -> Result<floe_engine::guard::Measures, String> {
        let mut e = self.take_recorder();
        let p = &self.gpu.programs;
        p.measure_partials.dispatch(&mut e, &self.core.measure, self.n);
        p.measure_total.dispatch(&mut e, &self.core.measure, PER_PARTIAL);
        let size = std::mem::size_of::<Measures>() as u64;
        let readback = self.buffers.get("measures_readback").clone();
        e.encoder.copy_buffer_to_buffer(self.buffers.get("partials"), 0, &readback, 0, size);
        self.submit(e);
        let got = self.read_mapped(&[(&readback, size)])?;
        Ok(bytemuck::pod_read_unaligned::<Measures>(bytemuck::cast_slice(&got[0])).into())
    }

    fn reduce(&mut self, r: &Reduction) -> Result<f64, String> {
        let (op, lo, hi) = match r.op {
            ReduceOp::Sum | ReduceOp::Mean | ReduceOp::Norm => (0, 0.0, 0.0),
            ReduceOp::Max => (1, 0.0, 0.0),
            ReduceOp::MaxAbs => (2, 0.0, 0.0),
            ReduceOp::Outside { min, max } => (3, min, max),
        };
        let (mut e, n) = self.record_reduction(r.attr, op, lo, hi)?;
        let readback = self.buffers.get("reduce_readback").clone();
        e.encoder.copy_buffer_to_buffer(self.buffers.get("reduce_partials"), 0, &readback, 0, 4);
        self.submit(e);
        let got = self.read_mapped(&[(&readback, 4)])?;
        let value = f64::from(f32::from_bits(got[0][0]));
        Ok(match r.op {
            ReduceOp::Mean => value / f64::from(n.max(1)),
            ReduceOp::Norm => value.sqrt(),
            _ => value,
        })
    }

    fn sum_into(&mut self, attr: &'static str, into: &'static str, slot: u32) {
        let (mut e, _) = self.record_reduction(attr, 0, 0.0, 0.0).unwrap_or_else(|e| panic!("sum_into: {e}"));
        let target = self.buffers.get(into);
        e.encoder.copy_buffer_to_buffer(self.buffers.get("reduce_partials"), 0, target, 4 * u64::from(slot), 4);
        // Submitted now: the next reduction rewrites the shared `reduce_words`.
        self.submit(e);
    }

    fn kick(&mut self, dt: Real, keep: Real) {
        let slot = self.write_step(Step { kick_dt: dt, keep, drift_dt: 0.0, transport: 0 });
        let mut e = self.take_recorder();
        self.gpu.programs.kick.dispatch(&mut e, &self.core.integrate[slot], self.n);
        self.pending = Some(e);
    }

    fn drift(&mut self, dt: Real) {
        let slot = self.write_step(Step { kick_dt: 0.0, keep: 1.0, drift_dt: dt, transport: self.transport });
        let mut e = self.take_recorder();
        self.gpu.programs.drift.dispatch(&mut e, &self.core.integrate[slot], self.n);
        self.pending = Some(e);
    }

    fn end_step(&mut self) {
        self.flush();
    }

    /// Recorded as a copy of the index into the `sweep` uniform, so the passes
    /// recorded after it read it (scenes without swept solves have neither buffer).
    fn sweep(&mut self, k: u32) {
        let b = &self.buffers;
        let (Some(values), Some(sweep)) = (b.find("sweep_values").cloned(), b.find("sweep").cloned()) else { return };
        let mut e = self.take_recorder();
        e.encoder.copy_buffer_to_buffer(&values, 4 * u64::from(k), &sweep, 0, 4);
        self.pending = Some(e);
    }

    fn particle_id(&mut self, slot: u32) -> u32 {
        self.flush();
        self.download_words(&[(self.buffers.get("id"), 4 * slot as u64, 4)])[0][0]
    }

    fn first_outside(&mut self, attr: &str, min: f32, max: f32) -> Option<(u32, f32)> {
        self.flush();
        match self.download(&[attr]).pop()? {
            Column::F32(values) => floe_engine::guard::first_outside(&values, min, max),
            _ => None,
        }
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> &'static str {
        "gpu"
    }

    /// (Recorded but unsubmitted work is not included: a step ends with a submission,
    /// and callers driving passes directly end them with [`Stages::end_step`].)
    fn download(&self, names: &[&str]) -> Vec<Column> {
        let stored: Vec<&str> =
            names.iter().map(|n| PACKED.iter().find(|(a, _)| a == n).map_or(*n, |(_, into)| *into)).collect();
        let ranges: Vec<(&Buffer, u64, u64)> = stored
            .iter()
            .map(|n| {
                let spec = self.model.layout.spec(n).unwrap_or_else(|| panic!("no attribute {n}"));
                (self.buffers.get(n), 0, 4 * spec.elem.gpu_words() as u64 * self.count(spec.space))
            })
            .collect();
        let words = self.download_words(&ranges);
        names
            .iter()
            .zip(words)
            .map(|(name, w)| match *name {
                "material" => Column::U32(w.chunks_exact(4).map(|v| f32::from_bits(v[3]) as u32).collect()),
                name => from_gpu_words(self.model.layout.spec(name).expect("checked above").elem, &w),
            })
            .collect()
    }

    fn upload(&mut self, name: &str, column: Column) {
        // Work recorded before must run before the new values land.
        self.flush();
        let q = &self.gpu.queue;
        match name {
            // The material index is the w of each position.
            "material" => {
                let Column::U32(m) = column else { panic!("materials are u32") };
                let mut words = self.download_words(&[(self.buffers.get("x"), 0, 16 * self.n as u64)]).remove(0);
                for (k, &id) in m.iter().enumerate() {
                    words[4 * k + 3] = (id as f32).to_bits();
                }
                q.write_buffer(self.buffers.get("x"), 0, bytemuck::cast_slice(&words));
            }
            "x" if self.model.layout.spec("material").is_some() => {
                let old = self.download_words(&[(self.buffers.get("x"), 0, 16 * self.n as u64)]).remove(0);
                let mut words = gpu_words(&column);
                for k in 0..self.n as usize {
                    words[4 * k + 3] = old[4 * k + 3];
                }
                q.write_buffer(self.buffers.get("x"), 0, bytemuck::cast_slice(&words));
            }
            _ => q.write_buffer(self.buffers.get(name), 0, bytemuck::cast_slice(&gpu_words(&column))),
        }
    }

    fn restored(&mut self) {
        // Densities (and anything else derived) for output right away; the next step
        // recomputes them identically.
        self.run(Stage::Sort, 0.0);
        self.run(Stage::Density, 0.0);
        self.flush();
    }

    fn retuned(&mut self) {
        let (gpu, b) = (&self.gpu, &mut self.buffers);
        gpu.queue.write_buffer(b.get("params"), 0, bytemuck::bytes_of(&Params::new(&self.model, &self.grid)));
        for (name, make) in crate::pass::uniforms() {
            if let (Some(buffer), Some(bytes)) = (b.find(name), make(&self.model)) {
                gpu.queue.write_buffer(buffer, 0, &bytes);
            }
        }
        // Attributes that came or went with a setting (XSPH), then the plan's bindings.
        let layout = &self.model.layout;
        b.retain(|name| layout.spec(name).is_some());
        for spec in layout.specs() {
            if b.find(spec.name).is_none() && !PACKED.iter().any(|(a, _)| *a == spec.name) {
                let room =
                    if spec.space == PARTICLES { self.model.particle_capacity() } else { layout.count(spec.space) };
                b.add(&gpu.device, spec, room as u64);
            }
        }
        self.reductions.clear();
        self.passes = plan_passes(&self.gpu, &self.model, &self.buffers);
    }

    fn model_mut(&mut self) -> &mut Model {
        &mut self.model
    }

    fn allocations(&self) -> Vec<Allocation> {
        let attrs = self.buffers.attrs().iter().map(|(s, buffer)| Allocation {
            name: s.name,
            module: s.module,
            space: s.space,
            bytes: buffer.size(),
        });
        let core = self.buffers.core_sizes().into_iter().map(|(name, bytes)| Allocation {
            name,
            module: "core",
            space: if name == "walls" { WALLS } else { PARTICLES },
            bytes,
        });
        // A uniform is named after its module or scheme, or `module.what` for a second
        // one, or after an index map (its counts), which names its module.
        let module_of = |name: &'static str| match self.model.maps.iter().find(|m| m.name == name) {
            Some(map) => map.member.module,
            None => name.split('.').next().unwrap_or(name),
        };
        let uniforms = self.buffers.uniforms().iter().map(|(name, buffer)| Allocation {
            name,
            module: module_of(name),
            space: "uniform",
            bytes: buffer.size(),
        });
        attrs.chain(core).chain(uniforms).collect()
    }

    fn passes_run(&self) -> Vec<&'static str> {
        self.ran.clone()
    }

    /// Counts the particles marked (a sum reduction, 4 bytes back); where there are
    /// some, copies the particles' state back, keeps the others in order and uploads
    /// it (a copy of the particle state, only in a step that removed particles).
    fn compact(&mut self) {
        self.remove_marked();
    }

    fn emit(&mut self, births: &floe_engine::population::Births, first_id: u32) {
        self.write_births(births, first_id);
    }

    fn set_particle_count(&mut self, n: usize) {
        self.resized(n as u32);
    }

    fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.timer.as_ref().map(|t| t.totals().to_vec()).unwrap_or_default()
    }

    fn device_memory(&self) -> Option<u64> {
        Some(self.buffers.bytes() + self.core.scan.bytes())
    }

    fn read_on_grid(&self, set: &SetSpec, channels: &[&str], grid: &PositionGrid) -> Particles {
        self.read_quantized(set, channels, grid)
    }
}
