//! [`GpuBackend`]: the engine's [`Backend`] with every particle pass on the GPU.
//!
//! A step records its passes into one command buffer per evaluation and waits
//! only for the 32-byte measures the time step and guard need (the kick and
//! drift that follow are submitted without waiting). The step sequence itself
//! (integrators, dt, guard, snapshots) is the engine's [`Clock`], shared with
//! the CPU backend.

use crate::buffers::{Binds, Buffers, STEP_SLOTS, vec4s};
use crate::context::GpuContext;
use crate::layout::{Measures, Params, QuantGrid, Step};
use crate::passes::measure::PER_PARTIAL;
use crate::program::Recorder;
use crate::timer::Timer;
use floe_engine::backend::{Backend, Particles};
use floe_engine::math::{Real, Vec3};
use floe_engine::model::{BuildError, Model};
use floe_engine::neighbors::Grid;
use floe_engine::quantize::PositionGrid;
use floe_engine::scene::Scene;
use floe_engine::stepping::{Clock, Passes, SortedState, by_identity};
use wgpu::Buffer;

/// One scene's fluid on the GPU.
#[derive(Debug)]
pub struct GpuBackend {
    gpu: GpuContext,
    model: Model,
    grid: Grid,
    n: u32,
    buffers: Buffers,
    binds: Binds,
    clock: Clock,
    /// Kicks and drifts recorded since the last submission.
    pending: Option<Recorder>,
    /// Per-kernel GPU time, when profiling (held by `pending` while recording).
    timer: Option<Timer>,
    /// Next free step uniform of `buffers.steps`.
    slot: usize,
}

impl GpuBackend {
    /// Uploads `model`'s initial state to the GPU of `gpu`.
    pub fn new(gpu: &GpuContext, mut model: Model) -> Result<Self, BuildError> {
        let grid = Grid::new(model.domain, model.kernel.support());
        // A scene too large for the device's memory is refused, not a panic.
        let oom = gpu.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let invalid = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let buffers = Buffers::new(gpu, &model, &grid)?;
        let binds = buffers.bind(gpu, grid.cell_count() as u32);
        let refused = pollster::block_on(invalid.pop()).or(pollster::block_on(oom.pop()));
        if let Some(e) = refused {
            return Err(BuildError::Backend(format!("the GPU cannot hold this scene: {e}")));
        }
        let n = model.particle_count() as u32;
        // The GPU holds the state from here on.
        model.positions = Vec::new();
        model.velocities = Vec::new();
        let clock = Clock::new(&model);
        let timer = gpu.profiling().then(|| Timer::new(&gpu.device, gpu.queue.get_timestamp_period()));
        Ok(Self { gpu: gpu.clone(), model, grid, n, buffers, binds, clock, pending: None, timer, slot: 0 })
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
            t.add(&self.download(&[(&buffer, 0, len)])[0]);
        }
        self.timer = timer;
    }

    /// Submits the kicks and drifts recorded so far, without waiting.
    /// [`Backend::step`] does this itself; callers driving [`Passes`] directly
    /// flush before reading the state.
    pub fn flush(&mut self) {
        if let Some(rec) = self.pending.take() {
            self.submit(rec);
        }
        self.slot = 0;
    }

    /// Records the stable counting sort by cell, the permutation of the state
    /// and the density pass.
    fn record_sort_and_density(&mut self) {
        let (n, cells) = (self.n, self.grid.cell_count() as u32);
        let mut e = self.take_recorder();
        let p = &self.gpu.programs;
        let (b, binds) = (&self.buffers, &self.binds);
        let copies = [(&b.pos2, &b.pos, 16), (&b.vel2, &b.vel, 16), (&b.acc2, &b.acc, 16), (&b.ids2, &b.ids, 4)];
        e.encoder.clear_buffer(&b.counts, 0, None);
        p.grid.count.dispatch(&mut e, &binds.grid, n);
        p.scan.record(&mut e, &binds.scan);
        p.grid.scatter.dispatch(&mut e, &binds.grid, n);
        p.grid.settle.dispatch(&mut e, &binds.grid, cells);
        for bind in [&binds.reorder_pos, &binds.reorder_vel, &binds.reorder_acc] {
            p.reorder.state.dispatch(&mut e, bind, n);
        }
        p.reorder.ids.dispatch(&mut e, &binds.reorder_ids, n);
        for (from, to, size) in copies {
            e.encoder.copy_buffer_to_buffer(from, 0, to, 0, size * n as u64);
        }
        p.density.dispatch(&mut e, &binds.density, n);
        self.pending = Some(e);
    }

    fn write_step(&mut self, step: Step) -> usize {
        let slot = self.slot;
        assert!(slot < STEP_SLOTS, "more kicks and drifts between two evaluations than step slots");
        self.slot += 1;
        self.gpu.queue.write_buffer(&self.buffers.steps[slot], 0, bytemuck::bytes_of(&step));
        slot
    }

    /// Copies byte ranges (multiples of 4 bytes) of buffers back to the CPU, one
    /// submission and one wait, as 4-byte words (aligned for any of the state's
    /// types). Panics if the device is lost (see [`GpuBackend::try_download`]).
    fn download(&self, ranges: &[(&Buffer, u64, u64)]) -> Vec<Vec<u32>> {
        self.try_download(ranges).unwrap_or_else(|e| panic!("{e}"))
    }

    /// [`GpuBackend::download`], or why the GPU could not deliver.
    fn try_download(&self, ranges: &[(&Buffer, u64, u64)]) -> Result<Vec<Vec<u32>>, String> {
        let device = &self.gpu.device;
        let mut e = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("floe readback") });
        let staging: Vec<Buffer> = ranges
            .iter()
            .map(|&(src, offset, size)| {
                let s = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback"),
                    size: size.max(4),
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                if size > 0 {
                    e.copy_buffer_to_buffer(src, offset, &s, 0, size);
                }
                s
            })
            .collect();
        self.gpu.queue.submit([e.finish()]);
        let mapped: Vec<(&Buffer, u64)> = staging.iter().zip(ranges).map(|(s, r)| (s, r.2)).collect();
        self.read_mapped(&mapped)
    }

    /// Maps readback buffers written by work already submitted, waits for them,
    /// and copies out their first `len` bytes as words.
    fn read_mapped(&self, staging: &[(&Buffer, u64)]) -> Result<Vec<Vec<u32>>, String> {
        let device = &self.gpu.device;
        let (tx, rx) = std::sync::mpsc::channel();
        for (s, _) in staging {
            let tx = tx.clone();
            s.map_async(wgpu::MapMode::Read, .., move |r| {
                let _ = tx.send(r);
            });
        }
        device
            .poll(wgpu::PollType::Wait { submission_index: None, timeout: None })
            .map_err(|e| format!("GPU device failed: {e}"))?;
        for _ in staging {
            rx.recv()
                .map_err(|e| format!("GPU readback lost: {e}"))?
                .map_err(|e| format!("GPU readback failed: {e}"))?;
        }
        staging
            .iter()
            .map(|&(s, len)| {
                let view = s.get_mapped_range(..).map_err(|e| format!("GPU readback failed: {e}"))?;
                let words = bytemuck::cast_slice(&view[..len as usize]).to_vec();
                drop(view);
                s.unmap();
                Ok(words)
            })
            .collect()
    }

    fn vec3s(words: &[u32]) -> Vec<Vec3> {
        bytemuck::cast_slice::<u32, [f32; 4]>(words).iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect()
    }
}

impl GpuBackend {
    /// Positions (f32, or quantised on the GPU to `grid`) and `channels`, in
    /// identity order, copied back in one submission.
    fn read_with(&self, channels: &[&str], grid: Option<&PositionGrid>) -> Particles {
        let (b, n) = (&self.buffers, self.n as u64);
        let want = |c| channels.contains(&c);
        let vel = want("velocity");
        let rho = want("density") || want("pressure");
        // Sorted-order data needs the ids; quantised positions come in identity order.
        let sorted = vel || rho || grid.is_none();
        if let Some(g) = grid {
            self.gpu.queue.write_buffer(&b.quant_grid, 0, bytemuck::bytes_of(&QuantGrid::from(g)));
            let encoder =
                self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("quantize") });
            let mut e = Recorder { encoder, timer: None };
            self.gpu.programs.quantize.dispatch(&mut e, &self.binds.quantize, self.n.div_ceil(2));
            self.gpu.queue.submit([e.encoder.finish()]);
        }
        let size = |on: bool, bytes: u64| if on { bytes * n } else { 0 };
        let got = self.download(&[
            (&b.ids, 0, size(sorted, 4)),
            (&b.pos, 0, size(grid.is_none(), 16)),
            (&b.vel, 0, size(vel, 16)),
            (&b.dens, 0, size(rho, 8)),
            (&b.codes, 0, if grid.is_some() { 12 * n.div_ceil(2) } else { 0 }),
        ]);
        let velocities = vel.then(|| Self::vec3s(&got[2]));
        let densities: Option<Vec<Real>> =
            rho.then(|| bytemuck::cast_slice::<u32, [f32; 2]>(&got[3]).iter().map(|d| d[0]).collect());
        let mut p = by_identity(
            channels,
            &got[0],
            &Self::vec3s(&got[1]),
            velocities.as_deref(),
            densities.as_deref(),
            &self.model.fluid.eos,
        );
        if let Some(g) = grid {
            let codes: &[u16] = bytemuck::cast_slice(&got[4]);
            p.positions = codes
                .chunks_exact(3)
                .take(self.n as usize)
                .map(|c| std::array::from_fn(|k| g.value(c[k], k)))
                .collect();
        }
        p
    }
}

impl Passes for GpuBackend {
    fn model(&self) -> &Model {
        &self.model
    }

    fn evaluate(&mut self) -> Result<floe_engine::guard::Measures, String> {
        self.record_sort_and_density();
        let mut e = self.take_recorder();
        let (p, b) = (&self.gpu.programs, &self.binds);
        let walls = self.model.boundary.len() as u32;
        if walls > 0 {
            p.wall_pressure.dispatch(&mut e, &b.wall_pressure, walls);
        }
        p.forces.dispatch(&mut e, &b.forces, self.n);
        p.measure.partials.dispatch(&mut e, &b.measure, self.n);
        p.measure.total.dispatch(&mut e, &b.measure, PER_PARTIAL);
        let (size, readback) = (std::mem::size_of::<Measures>() as u64, &self.buffers.measures_readback);
        e.encoder.copy_buffer_to_buffer(&self.buffers.partials, 0, readback, 0, size);
        let readback = readback.clone();
        self.submit(e);
        let got = self.read_mapped(&[(&readback, size)])?;
        Ok(bytemuck::pod_read_unaligned::<Measures>(bytemuck::cast_slice(&got[0])).into())
    }

    fn kick(&mut self, dt: Real, keep: Real, with_xsph: bool) {
        let slot = self.write_step(Step { kick_dt: dt, keep, with_xsph: with_xsph as u32, drift_dt: 0.0 });
        let mut e = self.take_recorder();
        self.gpu.programs.integrate.kick.dispatch(&mut e, &self.binds.integrate[slot], self.n);
        self.pending = Some(e);
    }

    fn drift(&mut self, dt: Real) {
        let slot = self.write_step(Step { kick_dt: 0.0, keep: 1.0, with_xsph: 0, drift_dt: dt });
        let mut e = self.take_recorder();
        self.gpu.programs.integrate.drift.dispatch(&mut e, &self.binds.integrate[slot], self.n);
        self.pending = Some(e);
    }

    fn end_step(&mut self) {
        self.flush();
    }

    fn particle_id(&mut self, slot: u32) -> u32 {
        self.flush();
        self.download(&[(&self.buffers.ids, 4 * slot as u64, 4)])[0][0]
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> &'static str {
        "gpu"
    }

    fn clock(&self) -> &Clock {
        &self.clock
    }

    fn clock_mut(&mut self) -> &mut Clock {
        &mut self.clock
    }

    fn particle_count(&self) -> usize {
        self.n as usize
    }

    fn sorted_state(&self) -> SortedState {
        let (b, n) = (&self.buffers, self.n as u64);
        let got = self.download(&[(&b.pos, 0, 16 * n), (&b.vel, 0, 16 * n), (&b.acc, 0, 16 * n), (&b.ids, 0, 4 * n)]);
        SortedState {
            pos: Self::vec3s(&got[0]),
            vel: Self::vec3s(&got[1]),
            acc: Self::vec3s(&got[2]),
            ids: got[3].clone(),
        }
    }

    fn restore_state(&mut self, s: SortedState) {
        let (q, b) = (&self.gpu.queue, &self.buffers);
        q.write_buffer(&b.pos, 0, bytemuck::cast_slice(&vec4s(&s.pos)));
        q.write_buffer(&b.vel, 0, bytemuck::cast_slice(&vec4s(&s.vel)));
        q.write_buffer(&b.acc, 0, bytemuck::cast_slice(&vec4s(&s.acc)));
        q.write_buffer(&b.ids, 0, bytemuck::cast_slice(&s.ids));
        // Densities for output right away; the next step recomputes them identically.
        self.record_sort_and_density();
        self.flush();
    }

    fn read(&self, channels: &[&str]) -> Particles {
        self.read_with(channels, None)
    }

    fn kernel_times(&self) -> Vec<(&'static str, f64, u64)> {
        self.timer.as_ref().map(|t| t.totals().to_vec()).unwrap_or_default()
    }

    fn device_memory(&self) -> Option<u64> {
        Some(self.buffers.bytes() + self.binds.scan.bytes())
    }

    fn read_on_grid(&self, channels: &[&str], grid: &PositionGrid) -> Particles {
        self.read_with(channels, Some(grid))
    }

    fn retune(&mut self, scene: &Scene) {
        self.model.retune(scene);
        self.clock.retune(&self.model);
        let params = Params::new(&self.model, &self.grid);
        self.gpu.queue.write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&params));
    }
}
