//! Plan passes on the GPU: each a WGSL kernel with its bindings named after the
//! buffers it uses (attributes by name, and the core's `params`, `starts`,
//! `walls`, ...), registered under the same pass name as its CPU half. The backend
//! binds them by name, so a module's pass needs no edit in the backend.
//!
//! Module constants travel in module uniforms (`fluid`, `wcsph`), which do not
//! count against the 8 storage buffers a kernel may bind (the portability floor
//! this project keeps; `tests/shaders.rs` counts them).

use crate::program::Access;
use floe_engine::model::Model;

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

/// Plan passes with no kernel of their own: the core's sort (a sequence of the
/// core's kernels) and the neighbour search, which the GPU does in every pass from
/// the sorted grid.
pub const HOST_PASSES: &[&str] = &["core.sort", "core.neighbours"];

/// Every plan pass the GPU implements: the core's, the schemes' and the modules'.
pub fn all() -> Vec<&'static GpuPass> {
    let core: &[&'static GpuPass] = &[&crate::passes::DENSITY_PASS];
    core.iter().chain(crate::schemes::PASSES).chain(crate::modules::PASSES).copied().collect()
}

/// The implementation of plan pass `name` for `model`.
pub fn find(name: &str, model: &Model) -> Option<&'static GpuPass> {
    all().into_iter().find(|p| p.name == name && (p.when)(model))
}

/// A module's or scheme's constants as a uniform buffer's bytes, when the scene has it.
pub type UniformSource = fn(&Model) -> Option<Vec<u8>>;

/// Every module uniform by name.
pub fn uniforms() -> Vec<(&'static str, UniformSource)> {
    crate::schemes::UNIFORMS.iter().chain(crate::modules::UNIFORMS).copied().collect()
}

/// Always.
pub fn always(_: &Model) -> bool {
    true
}
