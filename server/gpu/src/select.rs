//! Choosing the backend a server or run uses: `auto | gpu | cpu`.

use crate::backend::GpuBackend;
use crate::context::{Adapters, GpuContext, GpuError};
use floe_engine::backend::Backend;
use floe_engine::simulation::{BackendFactory, cpu_backend};
use std::sync::Arc;

/// What the user asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BackendChoice {
    /// A hardware GPU when there is one, else the CPU.
    #[default]
    Auto,
    /// A GPU, software adapters (Mesa's lavapipe) included; an error if none.
    Gpu,
    /// The CPU backend (rayon).
    Cpu,
}

impl std::str::FromStr for BackendChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "gpu" => Ok(Self::Gpu),
            "cpu" => Ok(Self::Cpu),
            other => Err(format!("unknown backend {other:?}: expected auto, gpu or cpu")),
        }
    }
}

/// The backend chosen: how to build it for each scene, and what it is.
#[derive(Clone)]
pub struct Selected {
    /// Builds a scene's backend.
    pub factory: Arc<BackendFactory>,
    /// `gpu` or `cpu`.
    pub name: &'static str,
    /// The device, and for `auto` why it was chosen.
    pub description: String,
}

impl std::fmt::Debug for Selected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Selected").field("name", &self.name).field("description", &self.description).finish()
    }
}

impl Selected {
    /// The CPU backend, for `reason`.
    pub fn cpu(reason: &str) -> Self {
        let threads = rayon_threads();
        Self { factory: Arc::new(cpu_backend), name: "cpu", description: format!("CPU ({threads} threads): {reason}") }
    }

    /// The GPU backend on `gpu`.
    pub fn gpu(gpu: GpuContext, reason: &str) -> Self {
        let description = format!("GPU {}: {reason}", gpu.describe());
        let factory = Arc::new(move |model| GpuBackend::new(&gpu, model).map(|b| Box::new(b) as Box<dyn Backend>));
        Self { factory, name: "gpu", description }
    }
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Resolves `choice` (logs the outcome and the reason).
pub fn select(choice: BackendChoice) -> Result<Selected, GpuError> {
    select_with(choice, false)
}

/// [`select`], with GPU scenes timing every kernel when `profile` is set.
pub fn select_with(choice: BackendChoice, profile: bool) -> Result<Selected, GpuError> {
    let selected = match choice {
        BackendChoice::Cpu => Selected::cpu("asked for"),
        BackendChoice::Gpu => Selected::gpu(GpuContext::new(Adapters::Any, profile)?, "asked for"),
        BackendChoice::Auto => match GpuContext::new(Adapters::Hardware, profile) {
            Ok(gpu) => Selected::gpu(gpu, "a hardware adapter was found"),
            Err(e) => Selected::cpu(&format!("no hardware GPU ({e})")),
        },
    };
    tracing::info!(backend = selected.name, "simulation backend: {}", selected.description);
    Ok(selected)
}
