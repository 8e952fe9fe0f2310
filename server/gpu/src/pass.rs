//! Plan passes on the GPU: each a WGSL kernel with its bindings named after the
//! buffers it uses (attributes by name, and the core's `params`, `starts`,
//! `walls`, ...), registered under the same pass name as its CPU half. The backend
//! binds them by name, so a module's pass needs no edit in the backend.
//!
//! Module constants travel in module uniforms (`fluid`, `wcsph`), which do not
//! count against the 8 storage buffers a kernel may bind (the portability floor
//! this project keeps; `tests/shaders.rs` counts them).
//!
//! A [`Fused`] kernel does several passes of one stage that walk the same
//! neighbours (walk.wgsl) in one walk. It may bind more than 8 storage buffers: a
//! scene uses it only where the device allows its bindings, and its passes' own
//! kernels otherwise ([`fusions`]).

use crate::program::Access;
use floe_engine::model::Model;
use floe_engine::plan::PassSpec;

/// A plan pass's GPU kernel.
#[derive(Debug)]
pub struct GpuPass {
    /// The plan pass it implements (`fluid.forces`).
    pub name: &'static str,
    /// Complete WGSL source (`common.wgsl` prepended for particle kernels).
    pub source: &'static str,
    /// Entry point.
    pub entry: &'static str,
    /// Binding `k`: how the kernel sees it and the buffer it binds, by name.
    pub bindings: &'static [(Access, &'static str)],
    /// One thread per element of this space.
    pub space: &'static str,
    /// Whether this variant fits the scene (passes with several variants).
    pub when: fn(&Model) -> bool,
}

/// One kernel doing several plan passes of a stage in one neighbour walk: the
/// walk costs more than most passes' terms, so a pass that walks the neighbours
/// another has just walked costs little more than its arithmetic when fused.
#[derive(Debug)]
pub struct Fused {
    /// The plan passes it does, in plan order; it runs in the first one's place.
    pub passes: &'static [&'static str],
    /// The kernel; its name (the passes joined by `+`) labels it in profiles.
    pub kernel: GpuPass,
}

impl Fused {
    /// Storage buffers the kernel binds.
    pub fn storage_buffers(&self) -> u32 {
        self.kernel.bindings.iter().filter(|(a, _)| *a != Access::Uniform).count() as u32
    }
}

/// Every fused kernel.
pub fn fused() -> &'static [&'static Fused] {
    crate::modules::FUSED
}

/// The fused kernels `model` runs on a device that binds at most `storage` storage
/// buffers per kernel, each with the plan indices of the passes it does. A fusion
/// applies when its passes are all in the plan, in one stage, its kernel fits the
/// scene and the device, none of its passes reads or writes what an earlier one of
/// them writes, and no pass between them in the plan conflicts with those it moves
/// ahead of that pass (a fused pass runs in the first one's place). A pass belongs
/// to one fusion at most.
pub fn fusions(model: &Model, storage: u32) -> Vec<(&'static Fused, Vec<usize>)> {
    let plan = model.plan.passes();
    let index = |name: &str| plan.iter().position(|p| p.name == name);
    let mut taken: Vec<usize> = Vec::new();
    let mut found = Vec::new();
    for &f in fused() {
        let Some(at) = f.passes.iter().map(|n| index(n)).collect::<Option<Vec<usize>>>() else { continue };
        let in_order = at.windows(2).all(|w| w[0] < w[1]);
        let one_stage = at.iter().all(|&k| plan[k].stage == plan[at[0]].stage);
        if !in_order || !one_stage || !(f.kernel.when)(model) || f.storage_buffers() > storage {
            continue;
        }
        if at.iter().any(|k| taken.contains(k)) {
            continue;
        }
        let moved_safely = at.iter().enumerate().skip(1).all(|(n, &k)| {
            let earlier_fused = at[..n].iter().map(|&e| plan[e]);
            let between = (at[0] + 1..k).filter(|b| !at.contains(b)).map(|b| plan[b]);
            earlier_fused.chain(between).all(|other| !conflict(other, plan[k]))
        });
        if moved_safely {
            taken.extend(&at);
            found.push((f, at));
        }
    }
    found
}

/// Whether `later` may not run before `earlier` finishes: one writes (or
/// accumulates into) what the other reads, writes or accumulates into.
fn conflict(earlier: &PassSpec, later: &PassSpec) -> bool {
    let outputs = |p: &PassSpec| p.writes.iter().chain(p.accumulates).copied().collect::<Vec<&str>>();
    let touches = |p: &PassSpec| p.reads.iter().chain(p.writes).chain(p.accumulates).copied().collect::<Vec<&str>>();
    let hits = |a: Vec<&str>, b: Vec<&str>| a.iter().any(|x| b.contains(x));
    hits(outputs(earlier), touches(later)) || hits(outputs(later), touches(earlier))
}

/// Plan passes with no kernel of their own: the core's sort (a sequence of the
/// core's kernels) and the neighbour search, which the GPU does in every pass from
/// the sorted grid.
pub const HOST_PASSES: &[&str] = &["core.sort", "core.neighbours"];

/// Every plan pass the GPU implements: the core's, the schemes' and the modules'.
pub fn all() -> Vec<&'static GpuPass> {
    let core: &[&'static GpuPass] = &[
        &crate::passes::DENSITY_PASS,
        &crate::passes::PREDICT_PASS,
        &crate::passes::VELOCITY_FROM_POSITIONS_PASS,
        &crate::passes::LOOK_AHEAD_PASS,
        &crate::passes::LOOK_BACK_PASS,
    ];
    let core = core.iter().chain(crate::viscosity::PASSES);
    let extra = EXTRA.read().expect("registry lock");
    let registered = extra.iter().flat_map(|m| m.passes);
    core.chain(crate::schemes::PASSES).chain(crate::modules::PASSES).chain(registered).copied().collect()
}

/// The GPU half of a module registered at run time (a module compiled outside
/// this crate, registered with floe-engine's `module::register`).
#[derive(Debug)]
pub struct GpuModule {
    /// Its id (as its `ModuleDef` has it).
    pub id: &'static str,
    /// Its passes.
    pub passes: &'static [&'static GpuPass],
    /// Its uniforms.
    pub uniforms: &'static [(&'static str, UniformSource)],
}

static EXTRA: std::sync::RwLock<Vec<&'static GpuModule>> = std::sync::RwLock::new(Vec::new());

/// Adds a module's GPU half (after the built-in ones); registering one twice
/// changes nothing.
pub fn register(module: &'static GpuModule) {
    let mut extra = EXTRA.write().expect("registry lock");
    if !extra.iter().any(|m| m.id == module.id) {
        extra.push(module);
    }
}

/// The implementation of plan pass `name` for `model`.
pub fn find(name: &str, model: &Model) -> Option<&'static GpuPass> {
    all().into_iter().find(|p| p.name == name && (p.when)(model))
}

/// A module's or scheme's constants as a uniform buffer's bytes, when the scene has it.
pub type UniformSource = fn(&Model) -> Option<Vec<u8>>;

/// Every module uniform by name.
pub fn uniforms() -> Vec<(&'static str, UniformSource)> {
    let core = std::iter::once(&crate::viscosity::UNIFORM);
    let extra = EXTRA.read().expect("registry lock");
    let registered = extra.iter().flat_map(|m| m.uniforms);
    core.chain(crate::schemes::UNIFORMS).chain(crate::modules::UNIFORMS).chain(registered).copied().collect()
}

/// Always.
pub fn always(_: &Model) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use floe_engine::scene::load::from_preset;

    fn model(preset: &str, overrides: &[&str]) -> Model {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        Model::build(&from_preset(preset, &overrides).expect("the preset loads")).expect("the scene builds")
    }

    #[test]
    fn the_force_pass_walks_for_conduction_where_the_device_allows() {
        let heat = model("convection", &["particle_spacing=0.02"]);
        let found = fusions(&heat, 16);
        assert_eq!(found.len(), 1);
        let (fused, covers) = &found[0];
        let names: Vec<&str> = covers.iter().map(|&k| heat.plan.passes()[k].name).collect();
        assert_eq!(names, ["fluid.forces", "heat.conduction"]);
        assert_eq!(fused.storage_buffers(), 10);
        // A device at the portability floor runs the two passes' own kernels.
        assert!(fusions(&heat, 8).is_empty());
        // Without pressure terms in the force pass (DFSPH) the kernel does not fit.
        assert!(fusions(&model("convection", &["particle_spacing=0.02", "solver.method=\"dfsph\""]), 16).is_empty());
        // Without heat there is nothing to fuse.
        assert!(fusions(&model("hydrostatic", &["particle_spacing=0.05"]), 16).is_empty());
    }

    #[test]
    fn passes_that_touch_each_others_outputs_conflict() {
        let pass = |name: &'static str, reads: &'static [&'static str], writes: &'static [&'static str]| PassSpec {
            name,
            module: "test",
            stage: floe_engine::plan::Stage::Force,
            reads,
            writes,
            accumulates: &[],
            tolerance: 0.0,
        };
        let forces = pass("forces", &["x", "rho"], &["a"]);
        assert!(!conflict(&forces, &pass("conduction", &["x", "rho", "temperature"], &["heat_rate"])));
        assert!(conflict(&forces, &pass("reads_a", &["a"], &["b"])));
        assert!(conflict(&pass("writes_rho", &["x"], &["rho"]), &forces));
        assert!(conflict(&forces, &pass("writes_a_too", &["x"], &["a"])));
    }
}
