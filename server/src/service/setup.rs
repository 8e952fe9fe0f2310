//! How a registry is set up: the server's limits and options, with their defaults.

use crate::auth::AuthMode;
use crate::quota::QuotaSet;
use std::time::Duration;

/// Server limits.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Scenes alive at once.
    pub max_scenes: usize,
    /// Fluid particles in one scene.
    pub max_particles: usize,
}

/// Default of [`Limits::max_scenes`].
pub const DEFAULT_MAX_SCENES: u64 = 64;
/// Default of [`Limits::max_particles`].
pub const DEFAULT_MAX_PARTICLES: u64 = 4_000_000;
/// Default of [`Options::checkpoint_every`] (s).
pub const DEFAULT_CHECKPOINT_SECONDS: u64 = 60;

impl Default for Limits {
    fn default() -> Self {
        Self { max_scenes: DEFAULT_MAX_SCENES as usize, max_particles: DEFAULT_MAX_PARTICLES as usize }
    }
}

/// How a registry is set up.
#[derive(Debug, Clone)]
pub struct Options {
    /// Server limits.
    pub limits: Limits,
    /// Server-wide quota defaults.
    pub quotas: QuotaSet,
    /// How calls are authenticated.
    pub auth: AuthMode,
    /// Origins besides the server's own that may open a WebSocket.
    pub origins: Vec<String>,
    /// Wall time a scene runs between periodic checkpoints.
    pub checkpoint_every: Duration,
    /// Directory of the terrain assets scenes may name (`--assets`); none: refused.
    pub assets: Option<std::path::PathBuf>,
    /// The backend scenes run on (`cpu` or `gpu`), what a scene asking for one is
    /// checked against.
    pub backend: &'static str,
    /// Whether a preset created without a resolution is sized to the backend
    /// ([`crate::sizing`]) or keeps its own.
    pub preset_size: PresetSize,
}

/// How a preset created without a `particle_spacing` is sized (`--preset-size`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PresetSize {
    /// The finest spacing the backend steps at real time or faster, measured
    /// ([`crate::sizing`]).
    Auto,
    /// The preset's own spacing.
    Full,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            limits: Limits::default(),
            quotas: QuotaSet::default(),
            auth: AuthMode::SingleUser,
            origins: Vec::new(),
            checkpoint_every: Duration::from_secs(DEFAULT_CHECKPOINT_SECONDS),
            assets: None,
            backend: "cpu",
            preset_size: PresetSize::Full,
        }
    }
}
