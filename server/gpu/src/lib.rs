//! # floe-gpu
//!
//! Floe's GPU backend: every pass of the engine's fluid step as a WGSL compute
//! shader on wgpu (Vulkan), with the CPU backend as its oracle. The state stays
//! on the GPU; each step reads back only the 32-byte reduction the time step
//! and the stability guard need, and frames only when someone asks for one.
//!
//! - [`context`]: adapter choice (hardware first; software such as Mesa's
//!   lavapipe when allowed), device, compiled kernels.
//! - [`passes`]: the core's kernels, one `.wgsl` each; [`pass`]: plan passes bound by
//!   name, with the schemes' and modules' halves in [`schemes`] and [`modules`], and
//!   the core's per-particle viscosity in [`viscosity`]; [`maps`]: the generic
//!   passes over index maps (gathers and segmented sums), for modules' passes.
//! - [`layout`]: the `#[repr(C)]` structs shared with WGSL.
//! - [`buffers`], [`backend`]: one scene's GPU memory and its `Backend`.
//! - [`select`]: `auto | gpu | cpu` for the server and the CLI.

pub mod backend;
pub mod buffers;
pub mod context;
pub mod layout;
pub mod maps;
pub mod modules;
pub mod pass;
pub mod passes;
pub mod program;
pub mod schemes;
pub mod select;
pub mod timer;
pub mod viscosity;

pub use backend::GpuBackend;
pub use context::{Adapters, GpuContext, GpuError};
pub use select::{BackendChoice, Selected};
