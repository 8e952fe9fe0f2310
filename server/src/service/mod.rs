//! The in-process service API: the scenes on this server and what can be done
//! to them. gRPC (and, next, REST and WebSocket) are thin adapters over it.
//!
//! - [`handle`]: the server's handle on one scene; commands to its worker.
//! - [`shared`]: what a scene's worker shares with the server's tasks (status, published state, events).
//! - [`worker`]: a scene's worker thread, which owns its simulation and steps it.
//! - [`frames`]: frame subscriptions with latest-frame semantics and shared encoding.

pub mod frames;
pub mod handle;
pub mod options;
pub mod shared;
mod worker;

use floe_engine::Simulation;
use floe_engine::scene::load::{self, Format};
use floe_engine::simulation::BackendFactory;
use frames::{FrameCache, Subscription};
pub use handle::{CommandError, MAX_STEPS_PER_REQUEST, SceneHandle};
use options::FrameRequest;
pub use shared::{Event, Published, Shared, State, Status};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, RwLock};

/// Why a request failed; each transport maps these to its own codes.
#[derive(Debug, thiserror::Error)]
pub enum ServiceError {
    /// No scene has this id.
    #[error("no scene with id {0}")]
    NotFound(u64),
    /// The request or the scene it carries is invalid; the message names the field.
    #[error("{0}")]
    InvalidArgument(String),
    /// The scene cannot do that in its current state.
    #[error("{0}")]
    FailedPrecondition(String),
    /// A server limit was reached.
    #[error("{0}")]
    ResourceExhausted(String),
}

/// At most the first 64 characters of `text`, for echoing client input in an error
/// message without letting a huge input make a huge message.
pub fn clip(text: &str) -> std::borrow::Cow<'_, str> {
    const MAX: usize = 64;
    match text.char_indices().nth(MAX) {
        Some((at, _)) => format!("{}... ({} bytes)", &text[..at], text.len()).into(),
        None => text.into(),
    }
}

/// Where a new scene comes from.
#[derive(Debug, Clone)]
pub enum SceneSource {
    /// A preset name.
    Preset(String),
    /// A full scene document.
    Document {
        /// The text.
        text: String,
        /// TOML or JSON.
        format: Format,
    },
}

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

impl Default for Limits {
    fn default() -> Self {
        Self { max_scenes: DEFAULT_MAX_SCENES as usize, max_particles: DEFAULT_MAX_PARTICLES as usize }
    }
}

#[derive(Debug)]
struct Entry {
    handle: Arc<SceneHandle>,
    cache: Arc<FrameCache>,
}

/// Every scene on this server.
pub struct Registry {
    scenes: RwLock<BTreeMap<u64, Entry>>,
    next_id: AtomicU64,
    limits: Limits,
    /// Builds each scene's backend (the one `--backend` chose at start-up).
    backend: Arc<BackendFactory>,
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registry").field("scenes", &self.scenes).field("limits", &self.limits).finish()
    }
}

impl Registry {
    /// An empty registry whose scenes run on the backends `backend` builds.
    pub fn new(limits: Limits, backend: Arc<BackendFactory>) -> Self {
        Self { scenes: RwLock::new(BTreeMap::new()), next_id: AtomicU64::new(1), limits, backend }
    }

    /// Builds a scene and starts its worker. Building samples every particle, so
    /// call it from a blocking context for large scenes.
    pub fn create(&self, source: SceneSource, overrides: &[String]) -> Result<Arc<SceneHandle>, ServiceError> {
        if self.scenes.read().expect("lock").len() >= self.limits.max_scenes {
            return Err(ServiceError::ResourceExhausted(format!(
                "the server holds its limit of {} scenes; delete one first",
                self.limits.max_scenes
            )));
        }
        let scene = match source {
            SceneSource::Preset(name) => load::from_preset(&name, overrides),
            SceneSource::Document { text, format } => load::from_str(&text, format, overrides),
        }
        .map_err(|e| ServiceError::InvalidArgument(e.to_string()))?;
        // Counted before the scene is built (every particle set the scene's modules
        // create), so a scene over the limit allocates nothing.
        let particles = floe_engine::modules::counts(&scene).iter().map(|(_, n)| *n).fold(0, u64::saturating_add);
        if particles > self.limits.max_particles as u64 {
            return Err(ServiceError::InvalidArgument(format!(
                "particle_spacing: the scene has {particles} particles, more than this server's limit of {}",
                self.limits.max_particles
            )));
        }
        let sim = Simulation::new(scene, &*self.backend).map_err(|e| ServiceError::InvalidArgument(e.to_string()))?;
        let id = self.next_id.fetch_add(1, Ordering::Relaxed);
        tracing::info!(scene = id, name = %sim.scene().name, particles = sim.particle_count(), "scene created");
        let handle = Arc::new(SceneHandle::spawn(id, sim, self.backend.clone()));
        let entry = Entry { handle: handle.clone(), cache: Arc::new(FrameCache::default()) };
        self.scenes.write().expect("lock").insert(id, entry);
        Ok(handle)
    }

    /// The scene with this id.
    pub fn get(&self, id: u64) -> Result<Arc<SceneHandle>, ServiceError> {
        self.scenes.read().expect("lock").get(&id).map(|e| e.handle.clone()).ok_or(ServiceError::NotFound(id))
    }

    /// Every scene, by id.
    pub fn list(&self) -> Vec<Arc<SceneHandle>> {
        self.scenes.read().expect("lock").values().map(|e| e.handle.clone()).collect()
    }

    /// Removes a scene and stops its worker (waits for the current step).
    pub fn delete(&self, id: u64) -> Result<Arc<SceneHandle>, ServiceError> {
        let entry = self.scenes.write().expect("lock").remove(&id).ok_or(ServiceError::NotFound(id))?;
        entry.handle.delete();
        tracing::info!(scene = id, "scene deleted");
        Ok(entry.handle)
    }

    /// A frame subscription to scene `id` with the options `request` asks for.
    pub fn subscribe(&self, id: u64, request: &FrameRequest) -> Result<Subscription, ServiceError> {
        let (handle, cache) = {
            let scenes = self.scenes.read().expect("lock");
            let e = scenes.get(&id).ok_or(ServiceError::NotFound(id))?;
            (e.handle.clone(), e.cache.clone())
        };
        let options = request.check(&handle.shared)?;
        Subscription::new(handle, cache, options).map_err(|e| ServiceError::InvalidArgument(e.to_string()))
    }

    /// Deletes every scene (server shutdown).
    pub fn shutdown(&self) {
        let ids: Vec<u64> = self.scenes.read().expect("lock").keys().copied().collect();
        for id in ids {
            let _ = self.delete(id);
        }
    }
}
