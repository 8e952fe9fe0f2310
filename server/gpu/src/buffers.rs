//! One scene's GPU memory: a buffer per attribute of the scene's layout (the
//! engine's declarations: a vec3 is stored as a vec4, and a particle's material
//! index rides in the w of its position instead of a buffer of its own), the
//! core's buffers (grid, sort, walls, reductions, frames), and the module uniforms.
//! Kernels bind them by name ([`Buffers::get`]).

use crate::context::GpuContext;
use crate::layout::{Constraint, MAX_MATERIALS, Measures, Params, QuantGrid, Step, Words};
use crate::passes::scan::MAX_LEN;
use floe_engine::attrs::{AttrSpec, Column, Elem};
use floe_engine::model::{BuildError, Model};
use floe_engine::neighbors::Grid;
use wgpu::util::DeviceExt;
use wgpu::{Buffer, BufferUsages as U, Device};

/// Kicks and drifts recorded between two submissions, at most (a leap-frog
/// step records kick and drift before its evaluation).
pub const STEP_SLOTS: usize = 4;

/// Attributes stored in another attribute's buffer: the material index is the w of
/// the position.
pub const PACKED: &[(&str, &str)] = &[("material", "x")];

/// Buffers of one scene.
#[derive(Debug)]
pub struct Buffers {
    /// The core's buffers by name.
    core: Vec<(&'static str, Buffer)>,
    /// One buffer per attribute (packed ones excepted).
    attrs: Vec<(&'static AttrSpec, Buffer)>,
    /// Module uniforms by name.
    uniforms: Vec<(&'static str, Buffer)>,
    /// Step uniforms, one per slot.
    pub steps: Vec<Buffer>,
    /// `Words` uniforms of the permutation, by stride.
    pub strides: Vec<(u32, Buffer)>,
}

fn storage(device: &Device, label: &str, size: u64, extra: U) -> Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: U::STORAGE | U::COPY_SRC | U::COPY_DST | extra,
        mapped_at_creation: false,
    })
}

fn init<T: bytemuck::Pod>(device: &Device, label: &str, data: &[T], usage: U) -> Buffer {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    // Bindings may not be empty: pad to one element (at least one vec4), the
    // smallest size a kernel binding an array of them accepts (a scene without
    // walls has no wall constraints).
    let padded = vec![0u8; std::mem::size_of::<T>().max(16)];
    let contents = if bytes.is_empty() { &padded[..] } else { bytes };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
}

/// An attribute's values as the GPU stores them: 32-bit words, vec3 (and each
/// column of a 3x3 matrix) padded to a vec4.
pub fn gpu_words(column: &Column) -> Vec<u32> {
    let padded = |x: glam::Vec3| [x.x, x.y, x.z, 0.0];
    match column {
        Column::Vec3(v) => v.iter().flat_map(|&x| padded(x)).map(f32::to_bits).collect(),
        Column::Mat3(v) => {
            v.iter().flat_map(|m| [m.x_axis, m.y_axis, m.z_axis]).flat_map(padded).map(f32::to_bits).collect()
        }
        other => other.words(),
    }
}

/// An attribute of type `elem` from its GPU words.
pub fn from_gpu_words(elem: Elem, words: &[u32]) -> Column {
    match elem {
        Elem::Vec3 => Column::Vec3(
            words
                .chunks_exact(4)
                .map(|w| glam::Vec3::new(f32::from_bits(w[0]), f32::from_bits(w[1]), f32::from_bits(w[2])))
                .collect(),
        ),
        Elem::Mat3 => Column::Mat3(
            words
                .chunks_exact(12)
                .map(|w| {
                    let col = |c: usize| {
                        glam::Vec3::new(f32::from_bits(w[c]), f32::from_bits(w[c + 1]), f32::from_bits(w[c + 2]))
                    };
                    glam::Mat3::from_cols(col(0), col(4), col(8))
                })
                .collect(),
        ),
        other => Column::from_words(other, words).expect("whole elements"),
    }
}

impl Buffers {
    /// Uploads `model`'s initial state (its columns, taken out of its layout); fails
    /// when the scene exceeds the device's limits, naming what does not fit.
    pub fn new(gpu: &GpuContext, model: &mut Model, grid: &Grid) -> Result<Self, BuildError> {
        let device = &gpu.device;
        // Room for every particle the scene may hold (births write into it).
        let n = model.particle_capacity() as u64;
        let cells = grid.cell_count() as u64;
        let too_big = |what: &str, bytes: u64| {
            BuildError::Backend(format!(
                "{what} needs a {bytes}-byte buffer; this GPU binds at most {} bytes",
                gpu.max_binding()
            ))
        };
        if cells + 1 > MAX_LEN {
            return Err(BuildError::Backend(format!(
                "the neighbour grid has {cells} cells, more than the GPU sort handles ({MAX_LEN}); \
                 shrink the domain or enlarge the particle spacing"
            )));
        }
        if model.materials.len() > MAX_MATERIALS {
            return Err(BuildError::Backend(format!(
                "the scene has {} materials; the GPU backend holds at most {MAX_MATERIALS} (run it on the CPU)",
                model.materials.len()
            )));
        }
        let columns = model.layout.take_columns();
        let material: Option<Vec<u32>> = columns.iter().find_map(|(s, c)| match (s.name, c) {
            ("material", Column::U32(m)) => Some(m.clone()),
            _ => None,
        });
        let mut attrs = Vec::new();
        let mut widest = 1;
        for (spec, column) in &columns {
            if PACKED.iter().any(|(a, _)| *a == spec.name) {
                continue;
            }
            let mut words = gpu_words(column);
            if spec.space == floe_engine::attrs::PARTICLES {
                words.resize(n as usize * spec.elem.gpu_words(), 0);
            }
            if spec.name == "x"
                && let Some(m) = &material
            {
                for (k, &id) in m.iter().enumerate() {
                    words[4 * k + 3] = (id as f32).to_bits();
                }
            }
            let bytes = 4 * words.len() as u64;
            if bytes > gpu.max_binding() {
                return Err(too_big(&format!("attribute {} ({})", spec.name, spec.module), bytes));
            }
            widest = widest.max(spec.elem.gpu_words() as u32);
            let buffer = init(device, spec.name, &words, U::STORAGE | U::COPY_SRC | U::COPY_DST);
            attrs.push((*spec, buffer));
        }
        let walls = &model.wall_particles;
        // Material 0's pseudo-masses (none in a scene without SPH particles).
        let psi = |k: usize| walls.psi.first().map_or(0.0, |psi| psi[k]);
        let wall_data: Vec<[f32; 4]> =
            walls.positions.iter().enumerate().map(|(k, p)| [p.x, p.y, p.z, psi(k)]).collect();
        // Particle run starts (counts before the scan), then the wall grid's fixed starts.
        let mut starts = vec![0u32; cells as usize + 1];
        starts.extend_from_slice(walls.grid.starts());
        let constraints = Constraint::all(&model.wall_constraints);
        let scratch = 4 * widest as u64 * n;
        if scratch > gpu.max_binding() {
            return Err(too_big("the sort", scratch));
        }
        let core = vec![
            ("params", init(device, "params", &[Params::new(model, grid)], U::UNIFORM | U::COPY_DST)),
            // The step's dt for the plan passes that bind it (x; the rest pads to 16 bytes).
            ("dt", init(device, "pass dt", &[[0.0f32; 4]], U::UNIFORM | U::COPY_DST)),
            ("starts", init(device, "cell and wall run starts", &starts, U::STORAGE | U::COPY_DST | U::COPY_SRC)),
            ("cell_rank", storage(device, "cell and rank", 8 * n, U::empty())),
            ("order", storage(device, "sort order", 4 * n, U::empty())),
            ("sort_scratch", storage(device, "sort scratch", scratch, U::empty())),
            ("walls", init(device, "wall particles", &wall_data, U::STORAGE)),
            ("constraints", init(device, "wall constraints", &constraints, U::STORAGE)),
            ("partials", storage(device, "measure partials", 32 * n.div_ceil(256).max(1), U::empty())),
            ("reduce_partials", storage(device, "reduction partials", 4 * n.div_ceil(256), U::empty())),
            ("reduce_words", init(device, "reduction", &[Words::default()], U::UNIFORM | U::COPY_DST)),
            ("quant_grid", init(device, "frame position grid", &[QuantGrid::default()], U::UNIFORM | U::COPY_DST)),
            ("codes", storage(device, "frame position codes", 12 * n.div_ceil(2), U::empty())),
            ("measures_readback", readback(device, "measures readback", std::mem::size_of::<Measures>() as u64)),
            ("reduce_readback", readback(device, "reduction readback", 4)),
        ];
        let mut uniforms: Vec<(&'static str, Buffer)> = crate::pass::uniforms()
            .into_iter()
            .filter_map(|(name, make)| {
                make(model).map(|bytes| (name, init(device, name, &bytes, U::UNIFORM | U::COPY_DST)))
            })
            .collect();
        // Each index map's counts, named after the map.
        for map in &model.maps {
            let c = floe_engine::maps::Counts::of(map, &model.layout);
            uniforms.push((
                map.name,
                init(device, map.name, &[c.segments, c.memberships, c.members, c.sorted], U::UNIFORM),
            ));
        }
        // The sweep index of swept solves: copied from `sweep_values` into the
        // `sweep` uniform between dispatches.
        let sweeps = model
            .velocity_solves
            .iter()
            .chain(&model.position_solves)
            .map(|s| s.sweeps.max(s.max_sweeps))
            .max()
            .unwrap_or(0);
        let mut core = core;
        if sweeps > 1 {
            let values: Vec<u32> = (0..sweeps).collect();
            core.push(("sweep", init(device, "sweep", &[0u32; 4], U::UNIFORM | U::COPY_DST)));
            core.push(("sweep_values", init(device, "sweep values", &values, U::STORAGE | U::COPY_SRC)));
        }
        let mut strides: Vec<(u32, Buffer)> = Vec::new();
        for (spec, _) in &attrs {
            let s = spec.elem.gpu_words() as u32;
            if !strides.iter().any(|(t, _)| *t == s) {
                let words = Words { n: model.particle_count() as u32, stride: s, ..Words::default() };
                strides.push((s, init(device, "permutation", &[words], U::UNIFORM | U::COPY_DST)));
            }
        }
        Ok(Self {
            core,
            attrs,
            uniforms,
            steps: (0..STEP_SLOTS)
                .map(|_| init(device, "step", &[Step::default()], U::UNIFORM | U::COPY_DST))
                .collect(),
            strides,
        })
    }

    /// The buffer called `name`: an attribute, a module uniform or a core buffer.
    pub fn get(&self, name: &str) -> &Buffer {
        self.find(name).unwrap_or_else(|| panic!("no GPU buffer {name}"))
    }

    /// The buffer called `name`, if the scene has one.
    pub fn find(&self, name: &str) -> Option<&Buffer> {
        let attr = self.attrs.iter().find(|(s, _)| s.name == name).map(|(_, b)| b);
        let uniform = || self.uniforms.iter().find(|(n, _)| *n == name).map(|(_, b)| b);
        let core = || self.core.iter().find(|(n, _)| *n == name).map(|(_, b)| b);
        attr.or_else(uniform).or_else(core)
    }

    /// The attributes with their buffers.
    pub fn attrs(&self) -> &[(&'static AttrSpec, Buffer)] {
        &self.attrs
    }

    /// The module uniforms with their names.
    pub fn uniforms(&self) -> &[(&'static str, Buffer)] {
        &self.uniforms
    }

    /// Adds a zeroed buffer for attribute `spec` (a setting switched a feature on).
    pub fn add(&mut self, device: &Device, spec: &'static AttrSpec, n: u64) {
        let buffer = storage(device, spec.name, 4 * spec.elem.gpu_words() as u64 * n, U::empty());
        self.attrs.push((spec, buffer));
    }

    /// Drops the buffers of attributes `keep` does not name.
    pub fn retain(&mut self, keep: impl Fn(&str) -> bool) {
        self.attrs.retain(|(s, _)| keep(s.name));
    }

    /// Bytes of every buffer.
    pub fn bytes(&self) -> u64 {
        let all = self.core.iter().map(|(_, b)| b).chain(self.attrs.iter().map(|(_, b)| b));
        let more = self.uniforms.iter().map(|(_, b)| b).chain(&self.steps).chain(self.strides.iter().map(|(_, b)| b));
        all.chain(more).map(|b| b.size()).sum()
    }

    /// Bytes of the core's buffers, by name.
    pub fn core_sizes(&self) -> Vec<(&'static str, u64)> {
        self.core.iter().map(|(n, b)| (*n, b.size())).collect()
    }
}

fn readback(device: &Device, label: &str, size: u64) -> Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: U::MAP_READ | U::COPY_DST,
        mapped_at_creation: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix's columns and a vec3 are padded to vec4s (WGSL's `mat3x3<f32>` and
    /// `vec3<f32>` array strides) and come back as they went.
    #[test]
    fn padded_types_round_trip() {
        let m = glam::Mat3::from_cols_array(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
        let c = Column::Mat3(vec![m, m.transpose()]);
        let words = gpu_words(&c);
        assert_eq!(words.len(), 2 * Elem::Mat3.gpu_words());
        assert_eq!(f32::from_bits(words[4]), 4.0, "the second column starts at word 4");
        assert_eq!(from_gpu_words(Elem::Mat3, &words), c);
        let q = Column::Quat(vec![glam::Quat::from_rotation_x(0.5)]);
        assert_eq!(from_gpu_words(Elem::Quat, &gpu_words(&q)), q);
    }
}
