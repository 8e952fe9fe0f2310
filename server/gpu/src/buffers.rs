//! One scene's GPU memory and the bind groups that tie it to the kernels.
//!
//! Per fluid particle: positions, velocities (vec4, w unused), accelerations
//! with the XSPH corrections behind them, the sort's scratch copies, ids and
//! their inverse, (density, p/rho^2), (cell, rank) and the permutation: about
//! 150 bytes, plus 4 bytes per grid cell.

use crate::context::GpuContext;
use crate::layout::{Constraint, Params, QuantGrid, Step};
use crate::passes::scan::{MAX_LEN, ScanPlan};
use bytemuck::Pod;
use floe_engine::model::{BuildError, Model};
use floe_engine::neighbors::Grid;
use wgpu::util::DeviceExt;
use wgpu::{BindGroup, Buffer, BufferUsages as U, Device};

/// Kicks and drifts recorded between two submissions, at most (a leap-frog
/// step records kick and drift before its evaluation).
pub const STEP_SLOTS: usize = 4;

/// Buffers of one scene.
#[derive(Debug)]
pub struct Buffers {
    pub params: Buffer,
    pub steps: Vec<Buffer>,
    pub pos: Buffer,
    pub vel: Buffer,
    /// Accelerations in `[0, n)`, XSPH corrections in `[n, 2n)`.
    pub acc: Buffer,
    pub pos2: Buffer,
    pub vel2: Buffer,
    pub acc2: Buffer,
    pub ids: Buffer,
    pub ids2: Buffer,
    pub slot_of: Buffer,
    pub dens: Buffer,
    pub cell_rank: Buffer,
    /// Per-cell counts, then (after the scan) run starts; `cells + 1` entries.
    pub counts: Buffer,
    pub order: Buffer,
    pub walls: Buffer,
    pub wall_start: Buffer,
    pub wall_p: Buffer,
    pub constraints: Buffer,
    pub partials: Buffer,
    /// The frame position grid, and positions quantised to it (16-bit codes,
    /// identity order, 6 bytes per particle).
    pub quant_grid: Buffer,
    pub codes: Buffer,
    /// Where each step's measures are copied for the CPU to map.
    pub measures_readback: Buffer,
}

/// Bind groups of one scene, one per kernel use.
#[derive(Debug)]
pub struct Binds {
    pub grid: BindGroup,
    pub scan: ScanPlan,
    pub reorder_pos: BindGroup,
    pub reorder_vel: BindGroup,
    pub reorder_acc: BindGroup,
    pub reorder_ids: BindGroup,
    pub density: BindGroup,
    pub wall_pressure: BindGroup,
    pub forces: BindGroup,
    pub measure: BindGroup,
    /// One per step slot.
    pub integrate: Vec<BindGroup>,
    pub quantize: BindGroup,
}

fn storage(device: &Device, label: &str, size: u64, extra: U) -> Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: U::STORAGE | U::COPY_SRC | U::COPY_DST | extra,
        mapped_at_creation: false,
    })
}

fn init<T: Pod>(device: &Device, label: &str, data: &[T], usage: U) -> Buffer {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    // Bindings may not be empty: pad to one vec4.
    let padded;
    let contents = if bytes.is_empty() {
        padded = [0u8; 16];
        &padded[..]
    } else {
        bytes
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
}

/// Positions or velocities as vec4 with `w = 0`.
pub fn vec4s(v: &[glam::Vec3]) -> Vec<[f32; 4]> {
    v.iter().map(|p| [p.x, p.y, p.z, 0.0]).collect()
}

impl Buffers {
    /// Uploads `model`'s initial state; fails when the scene exceeds the device's limits.
    pub fn new(gpu: &GpuContext, model: &Model, grid: &Grid) -> Result<Self, BuildError> {
        let device = &gpu.device;
        let n = model.particle_count() as u64;
        let cells = grid.cell_count() as u64;
        let biggest = 32 * n;
        if biggest > gpu.max_binding() {
            return Err(BuildError::Backend(format!(
                "{n} particles need a {biggest}-byte buffer; this GPU binds at most {} bytes",
                gpu.max_binding()
            )));
        }
        if cells + 1 > MAX_LEN {
            return Err(BuildError::Backend(format!(
                "the neighbour grid has {cells} cells, more than the GPU sort handles ({MAX_LEN}); \
                 shrink the domain or enlarge the particle spacing"
            )));
        }
        let walls = &model.boundary;
        let wall_data: Vec<[f32; 4]> =
            walls.positions.iter().zip(&walls.psi).map(|(p, &psi)| [p.x, p.y, p.z, psi]).collect();
        let constraints: Vec<Constraint> = model.walls.iter().map(Constraint::from).collect();
        let ids: Vec<u32> = (0..n as u32).collect();
        let zeros4 = vec![[0.0f32; 4]; 2 * n as usize];
        Ok(Self {
            params: init(device, "params", &[Params::new(model, grid)], U::UNIFORM | U::COPY_DST),
            steps: (0..STEP_SLOTS)
                .map(|_| init(device, "step", &[Step::default()], U::UNIFORM | U::COPY_DST))
                .collect(),
            pos: init(device, "positions", &vec4s(&model.positions), U::STORAGE | U::COPY_SRC | U::COPY_DST),
            vel: init(device, "velocities", &vec4s(&model.velocities), U::STORAGE | U::COPY_SRC | U::COPY_DST),
            acc: init(device, "accelerations and XSPH", &zeros4, U::STORAGE | U::COPY_SRC | U::COPY_DST),
            pos2: storage(device, "positions (sorted)", 16 * n, U::empty()),
            vel2: storage(device, "velocities (sorted)", 16 * n, U::empty()),
            acc2: storage(device, "accelerations (sorted)", 16 * n, U::empty()),
            ids: init(device, "ids", &ids, U::STORAGE | U::COPY_SRC | U::COPY_DST),
            ids2: storage(device, "ids (sorted)", 4 * n, U::empty()),
            slot_of: init(device, "slot of id", &ids, U::STORAGE | U::COPY_SRC | U::COPY_DST),
            dens: storage(device, "density and p/rho^2", 8 * n, U::empty()),
            cell_rank: storage(device, "cell and rank", 8 * n, U::empty()),
            counts: storage(device, "cell counts and starts", 4 * (cells + 1), U::empty()),
            order: storage(device, "sort order", 4 * n, U::empty()),
            walls: init(device, "wall particles", &wall_data, U::STORAGE),
            wall_start: init(device, "wall cell starts", walls.grid.starts(), U::STORAGE),
            wall_p: storage(device, "wall pressures", 4 * walls.len() as u64, U::empty()),
            constraints: init(device, "wall constraints", &constraints, U::STORAGE),
            partials: storage(device, "measure partials", 32 * n.div_ceil(256), U::empty()),
            quant_grid: init(device, "frame position grid", &[QuantGrid::default()], U::UNIFORM | U::COPY_DST),
            codes: storage(device, "frame position codes", 12 * n.div_ceil(2), U::empty()),
            measures_readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("measures readback"),
                size: std::mem::size_of::<crate::layout::Measures>() as u64,
                usage: U::MAP_READ | U::COPY_DST,
                mapped_at_creation: false,
            }),
        })
    }

    /// Bytes of every buffer.
    pub fn bytes(&self) -> u64 {
        let all = [
            &self.params,
            &self.pos,
            &self.vel,
            &self.acc,
            &self.pos2,
            &self.vel2,
            &self.acc2,
            &self.ids,
            &self.ids2,
            &self.slot_of,
            &self.dens,
            &self.cell_rank,
            &self.counts,
            &self.order,
            &self.walls,
            &self.wall_start,
            &self.wall_p,
            &self.constraints,
            &self.partials,
            &self.quant_grid,
            &self.codes,
            &self.measures_readback,
        ];
        all.iter().chain(&self.steps.iter().collect::<Vec<_>>()).map(|b| b.size()).sum()
    }

    /// Every bind group the step needs.
    pub fn bind(&self, gpu: &GpuContext, cells: u32) -> Binds {
        let d = &gpu.device;
        let p = &gpu.programs;
        let reorder = |src: &Buffer, dst: &Buffer| p.reorder.state.bind(d, &[&self.params, &self.order, src, dst]);
        Binds {
            grid: p.grid.count.bind(d, &[&self.params, &self.pos, &self.cell_rank, &self.counts, &self.order]),
            scan: p.scan.plan(d, &self.counts, cells + 1),
            reorder_pos: reorder(&self.pos, &self.pos2),
            reorder_vel: reorder(&self.vel, &self.vel2),
            reorder_acc: reorder(&self.acc, &self.acc2),
            reorder_ids: p.reorder.ids.bind(d, &[&self.params, &self.order, &self.ids, &self.ids2, &self.slot_of]),
            density: p
                .density
                .bind(d, &[&self.params, &self.pos, &self.counts, &self.walls, &self.wall_start, &self.dens]),
            wall_pressure: p
                .wall_pressure
                .bind(d, &[&self.params, &self.pos, &self.counts, &self.walls, &self.dens, &self.wall_p]),
            forces: p.forces.bind(
                d,
                &[
                    &self.params,
                    &self.pos,
                    &self.vel,
                    &self.dens,
                    &self.counts,
                    &self.walls,
                    &self.wall_start,
                    &self.wall_p,
                    &self.acc,
                ],
            ),
            measure: p
                .measure
                .partials
                .bind(d, &[&self.params, &self.pos, &self.vel, &self.acc, &self.dens, &self.partials]),
            integrate: self
                .steps
                .iter()
                .map(|s| {
                    p.integrate.kick.bind(d, &[&self.params, s, &self.pos, &self.vel, &self.acc, &self.constraints])
                })
                .collect(),
            quantize: p.quantize.bind(d, &[&self.params, &self.quant_grid, &self.pos, &self.slot_of, &self.codes]),
        }
    }
}
