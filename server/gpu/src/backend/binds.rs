//! The bind groups of a scene's kernels: the core's own (sort, measures, kick and
//! drift, quantiser) and each plan pass's, with the fused kernels the device allows.

use crate::buffers::Buffers;
use crate::context::GpuContext;
use crate::passes::scan::ScanPlan;
use crate::program::Kernel;
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::neighbors::Grid;
use floe_engine::plan::PassSpec;
use std::sync::Arc;
use wgpu::{BindGroup, Buffer};

/// A plan pass ready to record: its kernel and bind group, or none for
/// [`crate::pass::HOST_PASSES`] (the sort: several kernels, recorded by
/// [`super::GpuBackend::record_sort`]).
#[derive(Debug)]
pub(super) struct PlanPass {
    pub(super) spec: &'static PassSpec,
    pub(super) kernel: Option<(Arc<Kernel>, BindGroup)>,
    /// Elements of the pass's space (threads).
    pub(super) threads: u32,
    /// Whether it reads the step's dt from the `dt` uniform.
    pub(super) uses_dt: bool,
    /// The fused kernel that does this pass and later ones of its stage when the
    /// stage runs as a whole ([`crate::pass::fusions`]), with their plan indices.
    pub(super) fused: Option<(Arc<Kernel>, BindGroup, Vec<usize>)>,
}

/// The bind groups of the core's own kernels.
#[derive(Debug)]
pub(super) struct CoreBinds {
    pub(super) grid: BindGroup,
    pub(super) scan: ScanPlan,
    /// Per state attribute of the particle space: its name, words per element and
    /// the permutation's bind group (into the scratch buffer).
    pub(super) permutes: Vec<(&'static str, u32, BindGroup)>,
    /// The slot of each id (none in a scene whose particles are born and die).
    pub(super) slots: Option<BindGroup>,
    pub(super) measure: BindGroup,
    /// One per step slot (kick and drift share a layout).
    pub(super) integrate: Vec<BindGroup>,
    /// Positions quantised in id order through `slot_of` (none without it).
    pub(super) quantize: Option<BindGroup>,
}

/// Binds the core's kernels to a scene's buffers.
pub(super) fn core_binds(gpu: &GpuContext, b: &Buffers, grid: &Grid) -> CoreBinds {
    let (d, p) = (&gpu.device, &gpu.programs);
    let stride = |s: u32| &b.strides.iter().find(|(t, _)| *t == s).expect("a uniform per stride").1;
    let permutes = b
        .attrs()
        .iter()
        .filter(|(s, _)| s.space == PARTICLES && s.role == floe_engine::attrs::Role::State)
        .map(|(s, buffer)| {
            let words = s.elem.gpu_words() as u32;
            let bind = p.permute.bind(d, &[stride(words), b.get("order"), buffer, b.get("sort_scratch")]);
            (s.name, words, bind)
        })
        .collect();
    CoreBinds {
        grid: p.grid_count.bind(d, &[b.get("params"), b.get("x"), b.get("cell_rank"), b.get("starts"), b.get("order")]),
        scan: p.scan.plan(d, b.get("starts"), grid.cell_count() as u32 + 1),
        permutes,
        slots: b.find("slot_of").map(|s| p.slots.bind(d, &[stride(1), b.get("order"), b.get("id"), s])),
        measure: p
            .measure_partials
            .bind(d, &[b.get("params"), b.get("x"), b.get("v"), b.get("a"), b.get("rho"), b.get("partials")]),
        integrate: b
            .steps
            .iter()
            .map(|s| {
                let (x, v, a) = (b.get("x"), b.get("v"), b.get("a"));
                // Scenes without a transport term bind `a` there; the drift reads it
                // only when its step says so. Scenes without terrain have no ground and
                // bind the constraints there (the drift reads heights only for a terrain).
                let transport = b.find("a_transport").unwrap_or(a);
                let ground = b.find("ground_height").unwrap_or(b.get("constraints"));
                p.kick.bind(d, &[b.get("params"), s, x, v, a, b.get("constraints"), ground, transport])
            })
            .collect(),
        quantize: b
            .find("slot_of")
            .map(|s| p.quantize.bind(d, &[b.get("params"), b.get("quant_grid"), b.get("x"), s, b.get("codes")])),
    }
}

/// Binds every plan pass (but the core's sort, recorded by hand) to its buffers,
/// and the fused kernels the device allows to the first pass each does.
pub(super) fn plan_passes(gpu: &GpuContext, model: &Model, b: &Buffers) -> Vec<PlanPass> {
    let bind = |pass: &'static crate::pass::GpuPass| {
        let kernel = gpu.kernel(pass);
        let buffers: Vec<&Buffer> = pass.bindings.iter().map(|(_, name)| b.get(name)).collect();
        let group = kernel.bind(&gpu.device, &buffers);
        (kernel, group)
    };
    let uses_dt = |pass: &crate::pass::GpuPass| pass.bindings.iter().any(|(_, name)| *name == "dt");
    let mut passes: Vec<PlanPass> = model
        .plan
        .passes()
        .iter()
        .map(|&spec| {
            if crate::pass::HOST_PASSES.contains(&spec.name) {
                let threads = model.particle_count() as u32;
                return PlanPass { spec, kernel: None, threads, uses_dt: false, fused: None };
            }
            let pass = crate::pass::find(spec.name, model).expect("checked at creation");
            let threads = model.layout.count(pass.space) as u32;
            PlanPass { spec, kernel: Some(bind(pass)), threads, uses_dt: uses_dt(pass), fused: None }
        })
        .collect();
    for (fused, covers) in crate::pass::fusions(model, gpu.max_storage_buffers()) {
        let first = &mut passes[covers[0]];
        let (kernel, group) = bind(&fused.kernel);
        first.uses_dt |= uses_dt(&fused.kernel);
        first.fused = Some((kernel, group, covers));
    }
    passes
}
