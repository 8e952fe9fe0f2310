//! The particles' population on the GPU: removing marked particles (a download,
//! the kept rows uploaded again) and writing births after the live ones.

use super::GpuBackend;
use crate::buffers::{PACKED, gpu_words};
use floe_engine::attrs::{Column, PARTICLES};
use floe_engine::backend::Backend;
use floe_engine::model::Model;
use floe_engine::scheme::{ReduceOp, Reduction, Stages};

impl GpuBackend {
    /// Removes the particles marked in `remove` (none marked: nothing read back),
    /// keeping the others' order.
    pub(super) fn remove_marked(&mut self) {
        let marked = self.reduce(&Reduction { attr: floe_engine::population::REMOVE.name, op: ReduceOp::Sum });
        if !marked.is_ok_and(|m| m > 0.0) {
            return;
        }
        let layout = &self.model.layout;
        let mut names: Vec<&'static str> = layout
            .specs()
            .filter(|s| s.space == PARTICLES && s.role == floe_engine::attrs::Role::State && s.name != "material")
            .map(|s| s.name)
            .collect();
        // The material after the positions, whose w it rides in.
        names.extend(layout.spec("material").map(|s| s.name));
        let remove = self.download(&[floe_engine::population::REMOVE.name]).remove(0);
        let Column::F32(remove) = remove else { unreachable!("remove is declared f32") };
        let keep: Vec<bool> = remove.iter().map(|&r| r == 0.0).collect();
        let columns = self.download(&names);
        let n = keep.iter().filter(|&&k| k).count();
        self.resized(n as u32);
        let zero = vec![0u8; 4 * remove.len()];
        self.gpu.queue.write_buffer(self.buffers.get(floe_engine::population::REMOVE.name), 0, &zero);
        for (name, column) in names.into_iter().zip(columns) {
            let mut attrs = floe_engine::attrs::Attrs::new(vec![(layout_spec(&self.model, name), column)]);
            attrs.retain(PARTICLES, &keep);
            let (_, kept) = attrs.into_columns().remove(0);
            self.upload(name, kept);
        }
    }

    /// Writes the births after the live particles: their positions (with their
    /// material in w), velocities and ids, every other attribute of theirs zero.
    pub(super) fn write_births(&mut self, births: &floe_engine::population::Births, first_id: u32) {
        self.flush();
        let (n, k) = (self.n as u64, births.len());
        let specs: Vec<&'static floe_engine::attrs::AttrSpec> = self
            .model
            .layout
            .specs()
            .filter(|s| s.space == PARTICLES && !PACKED.iter().any(|(a, _)| *a == s.name))
            .collect();
        for spec in specs {
            let column = match spec.name {
                "x" => {
                    let mut words = gpu_words(&Column::Vec3(births.x.clone()));
                    if self.model.layout.spec("material").is_some() {
                        for (j, &m) in births.material.iter().enumerate() {
                            words[4 * j + 3] = (m as f32).to_bits();
                        }
                    }
                    words
                }
                "v" => gpu_words(&Column::Vec3(births.v.clone())),
                "id" => (first_id..first_id + k as u32).collect(),
                _ => gpu_words(&Column::zeros(spec.elem, k)),
            };
            let at = 4 * spec.elem.gpu_words() as u64 * n;
            self.gpu.queue.write_buffer(self.buffers.get(spec.name), at, bytemuck::cast_slice(&column));
        }
        self.resized((n as usize + k) as u32);
    }
}

/// The declaration of attribute `name` of `model` (one it has).
fn layout_spec(model: &Model, name: &str) -> &'static floe_engine::attrs::AttrSpec {
    model.layout.spec(name).unwrap_or_else(|| panic!("no attribute {name}"))
}
