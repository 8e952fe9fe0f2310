//! The in-process service API: the scenes on this server, who may do what to
//! them, and what survives a restart. gRPC, REST and WebSocket are thin adapters
//! over it, so every transport gets the same ownership checks and quotas.
//!
//! - [`handle`]: the server's handle on one scene; commands to its worker.
//! - [`shared`]: what a scene's worker shares with the server's tasks (status, published state, events).
//! - [`worker`]: a scene's worker thread, which owns its simulation and steps it.
//! - [`frames`]: frame subscriptions with latest-frame semantics and shared encoding.
//! - [`pump`]: moves a subscription's frames to a transport until either side ends.
//! - `control`: the calls with consequences beyond the scene (quotas, checkpoints,
//!   share links, users); `persist`: bringing scenes back at start-up, checkpoints
//!   while running, and shutdown; `membership`: a cluster worker's side (scenes
//!   placed here taken up, scenes that moved dropped, draining).

mod control;
mod error;
pub mod frames;
pub mod handle;
mod membership;
pub mod options;
mod persist;
pub mod pump;
mod setup;
pub mod shared;
pub mod view;
mod worker;

use crate::auth::{Access, Caller};
use crate::cluster::{Member, Tenure};
use crate::metrics::{Metrics, SceneSample, SceneSamples};
use crate::quota::{Limit, QuotaSet, Quotas, StreamPermit};
use crate::store::Store;
pub use control::{UserView, require_admin};
pub use error::ServiceError;
use error::unavailable;
use floe_engine::Simulation;
use floe_engine::scene::load::{self, Format};
use floe_engine::simulation::BackendFactory;
use frames::{FrameCache, Subscription};
pub use handle::{CommandError, MAX_STEPS_PER_REQUEST, SceneHandle};
use options::FrameRequest;
pub use setup::{DEFAULT_CHECKPOINT_SECONDS, DEFAULT_MAX_PARTICLES, DEFAULT_MAX_SCENES, Limits, Options, PresetSize};
pub use shared::{Event, Published, Shared, State, Status};
use std::collections::{BTreeMap, HashMap};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, RwLock};
use std::time::Duration;

/// A scene another worker of the cluster holds, as the database records it.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// Scene id.
    pub id: u64,
    /// The worker holding it.
    pub worker: String,
    /// The user who created it.
    pub owner: String,
    /// Scene name.
    pub name: String,
    /// `paused`, `running` or `halted` as last recorded.
    pub state: String,
    /// Particles.
    pub particles: u64,
    /// Its figures as its worker published them with its last heartbeat.
    pub live: Option<crate::metrics::SceneSample>,
}

/// Where a new scene should be built.
#[derive(Debug, Clone, Copy, Default)]
pub struct Placing<'a> {
    /// The worker the request named ([`crate::cluster::WORKER_HEADER`]): a creation
    /// that followed placement's answer.
    pub worker: Option<&'a str>,
    /// The backend the scene must run on (`gpu`, `cpu`); `None` or empty: any.
    pub backend: Option<&'a str>,
    /// How a preset without a `particle_spacing` is sized; `None`: as the server's
    /// [`Options::preset_size`] says.
    pub size: Option<PresetSize>,
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

/// What a call does to a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Need {
    /// Reads it or watches its frames and events: its owner, an admin or a share link.
    Watch,
    /// Changes, steps, snapshots or deletes it: its owner or an admin.
    Steer,
}

#[derive(Debug)]
struct Entry {
    handle: Arc<SceneHandle>,
    cache: Arc<FrameCache>,
    /// Serialises this scene's checkpoints; holds what makes the next one due.
    checkpoint: Arc<tokio::sync::Mutex<Since>>,
}

/// What happened to a scene since its last checkpoint.
#[derive(Debug, Default)]
struct Since {
    /// Wall time it has run (a periodic checkpoint is due at `checkpoint_every`).
    running: Duration,
    /// Stepped by hand (or may have been: a step call whose caller left) since: the
    /// maintenance loop writes one at its next tick.
    stepped: bool,
}

/// Every scene on a server, shared with the metrics.
#[derive(Debug, Default)]
pub struct Scenes(RwLock<BTreeMap<u64, Entry>>);

impl SceneSamples for Scenes {
    fn samples(&self) -> Vec<SceneSample> {
        let scenes = self.0.read().expect("lock");
        scenes
            .values()
            .map(|e| {
                let sh = &e.handle.shared;
                let s = sh.status();
                SceneSample {
                    id: sh.id,
                    owner: sh.owner.clone(),
                    name: sh.name.clone(),
                    steps: s.steps,
                    steps_per_second: s.steps_per_second,
                    particles: sh.particles as u64,
                    sim_time: s.time,
                    subscribers: u64::from(sh.subscribers.load(Ordering::Relaxed)),
                    frames_published: sh.published.load(Ordering::Relaxed),
                    frame_bytes: sh.frame_bytes.load(Ordering::Relaxed),
                    dropped_frames: sh.dropped_frames(),
                    running: s.state == State::Running,
                    passes: sh.passes.lock().expect("lock").clone(),
                }
            })
            .collect()
    }
}

/// Every scene on this server, who may use them, and what keeps them.
pub struct Registry {
    scenes: Arc<Scenes>,
    next_id: AtomicU64,
    options: Options,
    /// Builds each scene's backend (the one `--backend` chose at start-up).
    backend: Arc<BackendFactory>,
    access: Access,
    quotas: Arc<Quotas>,
    metrics: Arc<Metrics>,
    /// The database and checkpoints; `None` keeps scenes in memory only.
    store: Option<Store>,
    /// This worker's membership of a cluster; `None` on a single server.
    member: Option<Member>,
    /// Scene threads step while it holds: the member's, or one that always holds.
    tenure: Arc<Tenure>,
    /// In a cluster, each scene not held here, as of the last maintenance tick:
    /// where a call for it goes, and what lists show of it.
    elsewhere: RwLock<BTreeMap<u64, Placed>>,
    /// In a cluster, the largest scene id the database knew at the last tick.
    newest_known: AtomicU64,
    /// Serialises the running-scene quota checks with the runs they admit.
    run_gate: tokio::sync::Mutex<()>,
    /// Each sized preset's size (by preset and overrides), measured once
    /// ([`crate::sizing`]).
    sizes: Mutex<HashMap<String, crate::sizing::Sizing>>,
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registry").field("scenes", &self.scenes).field("options", &self.options).finish()
    }
}

impl Registry {
    /// An empty registry kept in memory only (nothing survives the process), whose
    /// scenes run on the backends `backend` builds.
    pub fn new(options: Options, backend: Arc<BackendFactory>) -> Self {
        Self::with_store(options, backend, None, None)
    }

    fn with_store(
        options: Options,
        backend: Arc<BackendFactory>,
        store: Option<Store>,
        member: Option<Member>,
    ) -> Self {
        let scenes = Arc::new(Scenes::default());
        let tenure = member.as_ref().map_or_else(|| Arc::new(Tenure::forever()), |m| m.tenure.clone());
        let metrics = Arc::new(Metrics::new(scenes.clone()));
        Self {
            scenes,
            next_id: AtomicU64::new(1),
            access: Access::new(options.auth, options.origins.clone()),
            quotas: Arc::new(Quotas::new(options.quotas, metrics.clone())),
            metrics,
            options,
            backend,
            store,
            member,
            tenure,
            elsewhere: RwLock::new(BTreeMap::new()),
            newest_known: AtomicU64::new(0),
            run_gate: tokio::sync::Mutex::new(()),
            sizes: Mutex::new(HashMap::new()),
        }
    }

    /// Authentication.
    pub fn access(&self) -> &Access {
        &self.access
    }

    /// The metrics.
    pub fn metrics(&self) -> &Metrics {
        &self.metrics
    }

    /// Whose quotas a caller's requests count against: the user, or for a share
    /// link the shared scene's owner.
    pub fn account(&self, caller: &Caller) -> String {
        match caller {
            Caller::User { name, .. } => name.to_string(),
            Caller::Viewer { scene } => self
                .scenes
                .0
                .read()
                .expect("lock")
                .get(scene)
                .map_or_else(|| format!("share of scene {scene}"), |e| e.handle.shared.owner.clone()),
        }
    }

    /// The quotas of `account`: the server's defaults with the user's overrides.
    pub fn quotas_of(&self, account: &str) -> QuotaSet {
        self.access.quotas_of(account, self.quotas.defaults())
    }

    /// Takes one request from the caller's request rate, or refuses it.
    pub fn admit(&self, caller: &Caller) -> Result<(), ServiceError> {
        let account = self.account(caller);
        self.quotas.admit(&account, &self.quotas_of(&account))
    }

    /// Whether `caller` may do `need` to scene `id`, owned by `owner`. Other users'
    /// scenes are NotFound, not PermissionDenied: their existence does not leak.
    fn check(caller: &Caller, id: u64, owner: &str, need: Need) -> Result<(), ServiceError> {
        match caller {
            Caller::User { name, admin } if *admin || **name == *owner => Ok(()),
            Caller::Viewer { scene } if *scene == id => match need {
                Need::Watch => Ok(()),
                Need::Steer => {
                    Err(ServiceError::PermissionDenied("a share link can watch this scene, not steer it".into()))
                }
            },
            _ => Err(ServiceError::NotFound(id)),
        }
    }

    fn entry<T>(&self, caller: &Caller, id: u64, need: Need, f: impl FnOnce(&Entry) -> T) -> Result<T, ServiceError> {
        let scenes = self.scenes.0.read().expect("lock");
        let Some(e) = scenes.get(&id) else { return Err(self.not_here(caller, id, need)) };
        Self::check(caller, id, &e.handle.shared.owner, need)?;
        Ok(f(e))
    }

    /// The answer for a scene this server does not hold: where it is, to a caller who
    /// may use it there; else not found.
    fn not_here(&self, caller: &Caller, id: u64, need: Need) -> ServiceError {
        match self.elsewhere.read().expect("lock").get(&id) {
            Some(p) => match Self::check(caller, id, &p.owner, need) {
                Ok(()) => ServiceError::Elsewhere {
                    worker: p.worker.clone(),
                    message: format!("scene {id} is on worker {}", p.worker),
                },
                Err(e) => e,
            },
            // Newer than every scene of the last tick: another worker may have just
            // created it; the next tick says where (or that it does not exist).
            None if self.member.is_some() && id > self.newest_known.load(Ordering::Relaxed) => {
                ServiceError::Unavailable(format!("scene {id} is not known to this worker yet; retry"))
            }
            None => ServiceError::NotFound(id),
        }
    }

    /// The scene with this id, if `caller` may do `need` to it.
    pub fn get(&self, caller: &Caller, id: u64, need: Need) -> Result<Arc<SceneHandle>, ServiceError> {
        self.entry(caller, id, need, |e| e.handle.clone())
    }

    /// Every scene `caller` may watch, by id.
    pub fn list(&self, caller: &Caller) -> Vec<Arc<SceneHandle>> {
        let scenes = self.scenes.0.read().expect("lock");
        scenes
            .iter()
            .filter(|(id, e)| Self::check(caller, **id, &e.handle.shared.owner, Need::Watch).is_ok())
            .map(|(_, e)| e.handle.clone())
            .collect()
    }

    /// Builds a scene owned by the calling user and starts its worker. Its size is
    /// checked against the server's limit and the user's quota before anything is
    /// allocated; building runs off the async workers.
    pub async fn create(
        &self,
        caller: &Caller,
        source: SceneSource,
        overrides: Vec<String>,
    ) -> Result<Arc<SceneHandle>, ServiceError> {
        self.create_routed(caller, source, overrides, Placing::default()).await
    }

    /// [`Registry::create`] placed as `placing` asks: on its backend, and in a
    /// cluster built here when the request named this worker and it has room, or
    /// when placement picks this worker; otherwise the answer is
    /// [`ServiceError::Elsewhere`], naming the worker placement picked.
    pub async fn create_routed(
        &self,
        caller: &Caller,
        source: SceneSource,
        overrides: Vec<String>,
        placing: Placing<'_>,
    ) -> Result<Arc<SceneHandle>, ServiceError> {
        let Caller::User { name: owner, .. } = caller else {
            return Err(ServiceError::PermissionDenied("a share link cannot create scenes".into()));
        };
        let backend = self.asked_backend(placing.backend)?;
        let max_scenes = self.options.limits.max_scenes;
        if self.member.is_none() && self.scenes.0.read().expect("lock").len() >= max_scenes {
            return Err(ServiceError::ResourceExhausted(format!(
                "the server holds its limit of {max_scenes} scenes; delete one first"
            )));
        }
        let (overrides, sizing) = self.sized(&source, overrides, placing.size).await?;
        let (server_max, quotas) = (self.options.limits.max_particles, self.quotas.clone());
        let quota = self.quotas_of(owner).get(Limit::ParticlesPerScene);
        let who = owner.to_string();
        let assets = self.options.assets.clone();
        let (scene, particles) = tokio::task::spawn_blocking(move || {
            let scene = match source {
                SceneSource::Preset(name) => load::from_preset(&name, &overrides),
                SceneSource::Document { text, format } => load::from_str(&text, format, &overrides),
            }
            .and_then(|scene| load::with_assets(scene, assets.as_deref()))
            .map_err(|e| ServiceError::InvalidArgument(e.to_string()))?;
            // Counted before the scene is built (every particle set the scene's modules
            // create), so a scene over the limit allocates nothing.
            let particles =
                floe_engine::module::counts(&scene).iter().map(|(_, n)| *n).fold(0, u64::saturating_add);
            if particles > server_max as u64 {
                return Err(ServiceError::InvalidArgument(format!(
                    "particle_spacing: the scene has {particles} particles, more than this server's limit of {server_max}"
                )));
            }
            if particles > quota {
                let detail = format!("{who}'s scenes may have at most {quota} particles; this one has {particles}");
                return Err(quotas.refuse(Limit::ParticlesPerScene, quota, detail));
            }
            Ok((scene, particles))
        })
        .await
        .expect("scene load task")?;
        self.place_here(particles, placing.worker, backend).await?;
        let backend = self.backend.clone();
        let sim = tokio::task::spawn_blocking(move || {
            Simulation::new(scene, &*backend).map_err(|e| ServiceError::InvalidArgument(e.to_string()))
        })
        .await
        .expect("scene build task")?;
        let lease = self.member.as_ref().map(Member::lease);
        let id = match (&self.store, &lease) {
            (Some(store), Some(_)) => store.db.take_scene_id().await.map_err(unavailable)?,
            _ => self.next_id.fetch_add(1, Ordering::Relaxed),
        };
        if let Some(store) = &self.store {
            store.db.insert_scene(&persist::row(id, owner, &sim, particles, lease)).await.map_err(unavailable)?;
        }
        tracing::info!(scene = id, owner = %owner, name = %sim.scene().name, particles = sim.particle_count(), "scene created");
        let handle = self.insert(id, owner.to_string(), sim);
        if let Some(sizing) = sizing {
            handle.shared.sized(sizing);
        }
        Ok(handle)
    }

    /// A preset created without a resolution, on a server that sizes presets: its
    /// overrides with the spacing chosen for this backend, and the choice
    /// ([`crate::sizing`], measured once per preset and overrides). Otherwise the
    /// overrides as they are.
    async fn sized(
        &self,
        source: &SceneSource,
        mut overrides: Vec<String>,
        size: Option<PresetSize>,
    ) -> Result<(Vec<String>, Option<crate::sizing::Sizing>), ServiceError> {
        let SceneSource::Preset(preset) = source else { return Ok((overrides, None)) };
        if size.unwrap_or(self.options.preset_size) == PresetSize::Full || crate::sizing::sets_spacing(&overrides) {
            return Ok((overrides, None));
        }
        let key = format!("{preset} {overrides:?}");
        let known = self.sizes.lock().expect("lock").get(&key).cloned();
        let sizing = match known {
            Some(s) => s,
            None => {
                let (name, o, backend) = (preset.clone(), overrides.clone(), self.backend.clone());
                let measured = tokio::task::spawn_blocking(move || crate::sizing::size(&name, &o, &*backend))
                    .await
                    .expect("sizing task")
                    .map_err(|e| ServiceError::InvalidArgument(e.to_string()))?;
                tracing::info!(
                    preset = %preset,
                    particles = measured.particles,
                    full = measured.full_particles,
                    rtf = measured.rtf,
                    "preset sized to the backend"
                );
                self.sizes.lock().expect("lock").insert(key, measured.clone());
                measured
            }
        };
        overrides.push(format!("particle_spacing={}", sizing.spacing));
        Ok((overrides, Some(sizing)))
    }

    /// Starts the worker of scene `id` and lists it.
    fn insert(&self, id: u64, owner: String, sim: Simulation) -> Arc<SceneHandle> {
        let handle = Arc::new(SceneHandle::spawn(id, owner, sim, self.backend.clone(), self.tenure.clone()));
        let entry = Entry {
            handle: handle.clone(),
            cache: Arc::new(FrameCache::default()),
            checkpoint: Arc::new(tokio::sync::Mutex::new(Since::default())),
        };
        self.scenes.0.write().expect("lock").insert(id, entry);
        handle
    }

    /// Deletes a scene: forgets it in the database, stops its worker (after the
    /// current step) and removes its checkpoints.
    pub async fn delete(&self, caller: &Caller, id: u64) -> Result<Arc<SceneHandle>, ServiceError> {
        self.entry(caller, id, Need::Steer, |_| ())?;
        if let Some(store) = &self.store {
            store.db.delete_scene(id, self.lease().as_ref()).await.map_err(|e| self.db_error(id, e))?;
        }
        let entry = self.scenes.0.write().expect("lock").remove(&id).ok_or(ServiceError::NotFound(id))?;
        let handle = entry.handle.clone();
        tokio::task::spawn_blocking(move || entry.handle.delete()).await.expect("scene stop task");
        if let Some(store) = &self.store {
            let checkpoints = store.checkpoints.clone();
            if let Err(e) = tokio::task::spawn_blocking(move || checkpoints.remove(id)).await.expect("remove task") {
                tracing::warn!(scene = id, "checkpoints left behind: {e}");
            }
        }
        if let Some(store) = &self.store
            && !self.access.directory().shares_of(id).is_empty()
        {
            self.reload_directory(store).await?;
        }
        tracing::info!(scene = id, "scene deleted");
        Ok(handle)
    }

    /// A frame subscription to scene `id`, counted as one of the account's open streams.
    pub fn subscribe(&self, caller: &Caller, id: u64, request: &FrameRequest) -> Result<pump::FrameFeed, ServiceError> {
        let (handle, cache) = self.entry(caller, id, Need::Watch, |e| (e.handle.clone(), e.cache.clone()))?;
        let options = request.check(&handle.shared)?;
        let permit = self.open_stream(caller)?;
        let shared = handle.shared.clone();
        let subscription =
            Subscription::new(handle, cache, options).map_err(|e| ServiceError::InvalidArgument(e.to_string()))?;
        Ok(pump::FrameFeed { subscription, permit, shared })
    }

    /// Scene `id`'s events, counted as one of the account's open streams.
    pub fn events(&self, caller: &Caller, id: u64) -> Result<pump::EventFeed, ServiceError> {
        let handle = self.get(caller, id, Need::Watch)?;
        Ok(pump::EventFeed { events: handle.shared.events.subscribe(), permit: self.open_stream(caller)? })
    }

    fn open_stream(&self, caller: &Caller) -> Result<StreamPermit, ServiceError> {
        let account = self.account(caller);
        self.quotas.open_stream(&account, &self.quotas_of(&account))
    }
}
