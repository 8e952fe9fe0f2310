//! What every backend (the CPU's and the GPU's) offers the rest of Floe.
//!
//! A backend holds a scene's attributes and runs its plan's passes; it offers a
//! scheme the [`Stages`] of a step, and the server its state: snapshot sections,
//! channels for frames and exports, what it allocated and which passes it ran.

use crate::attrs::{Allocation, Column};
use crate::channels::{SetSpec, Source};
use crate::model::Model;
use crate::quantize::PositionGrid;
use crate::scheme::Stages;
pub use crate::scheme::StepReport;
pub use floe_proto::Particles;
use floe_proto::Values;

/// One attribute's values in a snapshot, in slot order.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The attribute.
    pub name: String,
    /// Its values.
    pub column: Column,
}

/// A simulation backend: owns the attributes and steps them.
pub trait Backend: Stages + Send {
    /// Short name (`cpu`, `gpu`).
    fn name(&self) -> &'static str;
    /// The values of attributes `names` in slot order (a GPU copies them back in one
    /// submission).
    fn download(&self, names: &[&str]) -> Vec<Column>;
    /// Replaces attribute `name`'s values (same type and length).
    fn upload(&mut self, name: &str, column: Column);
    /// Takes restored state: every state attribute's section was uploaded; the
    /// backend re-sorts and recomputes derived attributes so output is right at once.
    fn restored(&mut self);
    /// Takes new tunable settings of the scene (the model is retuned by the caller's
    /// [`Backend::retune`] default); follows attributes and passes that came or went.
    fn retuned(&mut self);
    /// The model, mutable (to retune).
    fn model_mut(&mut self) -> &mut Model;
    /// What each attribute takes (bytes), with the module that declared it.
    fn allocations(&self) -> Vec<Allocation>;
    /// The names of every pass this backend has run (core, scheme and modules), in
    /// the order each first ran.
    fn passes_run(&self) -> Vec<&'static str>;

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
    /// Takes new tunable settings (see [`crate::scene::tunable`]) from `scene`.
    fn retune(&mut self, scene: &crate::scene::Scene) {
        self.model_mut().retune(scene);
        self.retuned();
    }
    /// Number of SPH particles.
    fn particle_count(&self) -> usize {
        self.model().particle_count()
    }
    /// Removes the particles the `remove` attribute marks, the others keeping their
    /// order (a scene with removal, after each step; see [`crate::population`]).
    fn compact(&mut self);
    /// Appends `births`, with ids from `first_id` on (within the scene's capacity,
    /// which the caller checked); their other attributes start at zero.
    fn emit(&mut self, births: &crate::population::Births, first_id: u32);
    /// Sets the number of live particles (a restored scene's), resizing what they hold.
    fn set_particle_count(&mut self, n: usize);
    /// Every state attribute's values, in slot order (a snapshot's sections).
    fn state(&self) -> Vec<Section> {
        let names: Vec<&'static str> =
            self.model().layout.specs().filter(|s| s.role == crate::attrs::Role::State).map(|s| s.name).collect();
        names.iter().zip(self.download(&names)).map(|(n, column)| Section { name: n.to_string(), column }).collect()
    }
    /// Positions and the channels `channels` of particle set `set`, in identity order.
    fn read_set(&self, set: &SetSpec, channels: &[&str]) -> Particles {
        read(self, set, channels, None)
    }
    /// Like [`Backend::read_set`], with positions that quantise on `grid` to the same
    /// codes as the exact ones: all a frame encoder quantising to `grid` needs. The
    /// exact positions qualify (this default, no extra work); a GPU quantises on the
    /// device, copies back 16-bit codes and returns their values.
    fn read_on_grid(&self, set: &SetSpec, channels: &[&str], grid: &PositionGrid) -> Particles {
        let _ = grid;
        self.read_set(set, channels)
    }
}

/// Reads set `set`'s channels from `b`, positions from `positions` when given (a
/// GPU's quantised ones, already in identity order) or else from the set's position
/// attribute.
pub fn read<B: Backend + ?Sized>(
    b: &B,
    set: &SetSpec,
    channels: &[&str],
    positions: Option<Vec<[f32; 3]>>,
) -> Particles {
    let model = b.model();
    let has_material = model.layout.spec("material").is_some() && set.space == crate::attrs::PARTICLES;
    let specs: Vec<_> = channels
        .iter()
        .map(|&c| {
            (model.channels.iter())
                .find(|s| s.name == c && s.set == set.channel_set())
                .unwrap_or_else(|| panic!("no channel {c}"))
        })
        .collect();
    // Every attribute needed, once: ids, positions, materials for a part, each
    // channel's sources.
    let mut names: Vec<&str> = set.id.into_iter().collect();
    if set.kind.is_some() && has_material {
        names.push("material");
    }
    if positions.is_none() && set.grid.is_none() {
        names.push(set.position);
    }
    for s in &specs {
        match s.source {
            Source::Attr(a) => names.push(a),
            Source::Derived { from, .. } => {
                names.extend(from);
                if has_material {
                    names.push("material");
                }
            }
        }
    }
    names.dedup();
    let mut unique: Vec<&str> = Vec::new();
    for n in names {
        if !unique.contains(&n) {
            unique.push(n);
        }
    }
    let columns = b.download(&unique);
    let column = |name: &str| &columns[unique.iter().position(|&n| n == name).expect("downloaded")];
    let ids: Option<&[u32]> = set.id.map(|id| match column(id) {
        Column::U32(v) => v.as_slice(),
        _ => panic!("ids are u32"),
    });
    // The slot of each particle in id order: the inverse of the ids where they are
    // 0 .. n (a scene whose particles are never born nor die), else the slots sorted
    // by id; for a part, only its members'.
    let mut sparse = false;
    let mut by_id: Option<Vec<usize>> = ids.map(|ids| {
        let n = ids.len();
        let mut by = vec![usize::MAX; n];
        for (k, &id) in ids.iter().enumerate() {
            match by.get_mut(id as usize) {
                Some(slot) => *slot = k,
                None => {
                    let mut sorted: Vec<usize> = (0..n).collect();
                    sorted.sort_unstable_by_key(|&k| ids[k]);
                    sparse = true;
                    return sorted;
                }
            }
        }
        by
    });
    if let (Some(kind), Some(by_id)) = (set.kind, by_id.as_mut()) {
        let materials = has_material.then(|| match column("material") {
            Column::U32(m) => m.as_slice(),
            _ => panic!("materials are u32"),
        });
        let member = |k: usize| model.materials.get(materials.map_or(0, |m| m[k]) as usize).kind == kind;
        by_id.retain(|&k| member(k));
        sparse = true;
    }
    let order = |values: Vec<f32>, components: usize| -> Vec<f32> {
        match &by_id {
            None => values,
            Some(by_id) => {
                let mut out = Vec::with_capacity(values.len());
                for &k in by_id {
                    out.extend_from_slice(&values[k * components..(k + 1) * components]);
                }
                out
            }
        }
    };
    let floats = |c: &Column| -> (Vec<f32>, usize) {
        match c {
            Column::F32(v) => (v.clone(), 1),
            Column::U32(v) => (v.iter().map(|&x| x as f32).collect(), 1),
            Column::Vec3(v) => (v.iter().flat_map(|x| x.to_array()).collect(), 3),
            Column::Vec4(v) => (v.iter().flatten().copied().collect(), 4),
            Column::Sym3(v) => (v.iter().flatten().copied().collect(), 6),
            Column::Mat3(v) => (v.iter().flat_map(|m| m.to_cols_array()).collect(), 9),
            Column::Quat(v) => (v.iter().flat_map(|q| q.to_array()).collect(), 4),
        }
    };
    let positions = positions.unwrap_or_else(|| {
        if set.grid.is_some() {
            return Vec::new();
        }
        let (p, _) = floats(column(set.position));
        order(p, 3).chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
    });
    let channels = specs
        .iter()
        .map(|s| {
            let (values, components) = match s.source {
                Source::Attr(a) => floats(column(a)),
                Source::Derived { from, values } => {
                    let mut inputs: Vec<Column> = from.iter().map(|&f| column(f).clone()).collect();
                    if has_material {
                        inputs.push(column("material").clone());
                    }
                    (values(model, &inputs), usize::from(s.components))
                }
            };
            let values = order(values, components);
            let values = if s.exact {
                Values::Exact(values.iter().map(|&v| v.clamp(0.0, 255.0) as u8).collect())
            } else {
                Values::Float { components: s.components, data: values }
            };
            (s.name.to_string(), values)
        })
        .collect();
    // Ids that are not 0 .. n travel with the particles (in id order).
    let live = match (ids, &by_id) {
        (Some(ids), Some(by_id)) if sparse => Some(by_id.iter().map(|&k| ids[k]).collect()),
        _ => None,
    };
    Particles { set: set.name.to_string(), positions, channels, grid: set.grid, ids: live }
}
