//! What a scene shares between its worker thread and the server's tasks: its
//! status, the latest particle state published for frame subscribers, its
//! events, and the subscribers' bookkeeping.

use floe_engine::Simulation;
use floe_engine::channels::ChannelSpec;
use floe_engine::quantize::PositionGrid;
use floe_engine::simulation::Measure;
use floe_proto::{ChannelKind, Particles};
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use tokio::sync::{broadcast, watch};

/// Whether a scene is stepping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Waiting for commands.
    Paused,
    /// Stepping continuously.
    Running,
    /// Stopped by the stability guard.
    Halted,
    /// Deleted; its worker has ended.
    Deleted,
}

/// What a scene is doing, updated by its worker after every step.
#[derive(Debug, Clone)]
pub struct Status {
    /// Running state.
    pub state: State,
    /// Simulated time (s).
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    /// The last dt (s).
    pub dt: f64,
    /// Steps per wall second over the last second of stepping.
    pub steps_per_second: f64,
    /// The halt message, when halted.
    pub halt_reason: Option<String>,
    /// What the scheme and modules measured, refreshed at most twice a second while
    /// running and whenever stepping stops.
    pub measures: Vec<Measure>,
}

/// Particle state published for frame subscribers, in identity order (the
/// latest one is held in [`Shared::published_state`]).
#[derive(Debug)]
pub struct Published {
    /// Counts up by one per published snapshot.
    pub sequence: u64,
    /// Step it was taken at.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Per particle set with subscribers (set 0 always): its index, positions and the
    /// channels they asked for.
    pub sets: Vec<(u8, Particles)>,
}

impl Published {
    /// The particles of set `set`, if they were read for this state.
    pub fn particles(&self, set: u8) -> Option<&Particles> {
        self.sets.iter().find(|(s, _)| *s == set).map(|(_, p)| p)
    }
}

/// Something that happened to a scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// The stability guard stopped it.
    Halted(floe_engine::Halted),
    /// Tunable settings changed (the overrides applied).
    ParameterChanged(Vec<String>),
    /// A step call's caller left: the server learned it at step `left_at` (steps
    /// taken), finished the step under way and stopped at `stopped_at`.
    StepAbandoned {
        /// Steps taken when the server learned the caller had left.
        left_at: u64,
        /// Steps taken when the stepping stopped.
        stopped_at: u64,
    },
    /// It was deleted.
    Deleted,
}

/// State shared between a scene's worker and the server's tasks.
#[derive(Debug)]
pub struct Shared {
    /// Scene id.
    pub id: u64,
    /// Scene name.
    pub name: String,
    /// The user who created it.
    pub owner: String,
    /// The resolved scene as JSON, as it is now (live changes included).
    pub(super) scene_json: Mutex<String>,
    /// Particles it may hold at once (its capacity, where particles are born and die):
    /// what the server's limits and quotas count.
    pub particles: usize,
    /// The channels the scene offers, with the tags its frames carry them under.
    pub channels: Vec<SceneChannel>,
    /// The scene's particle sets; a frame's set byte is an index into this list.
    pub sets: Vec<SceneSet>,
    /// The settings that may change while the scene exists.
    pub tunables: Vec<floe_engine::scene::tunable::Tunable>,
    /// The scene's materials (shared with the model: they never change).
    pub materials: Arc<floe_engine::materials::Materials>,
    /// Particle spacing (m).
    pub particle_spacing: f32,
    /// The backend stepping the scene (`gpu`, `cpu`); resets and restores keep it.
    pub backend: &'static str,
    /// Domain (m): frames quantise positions over it.
    pub bounds: ([f32; 3], [f32; 3]),
    /// Each terrain's heights with its index in the scene's boundaries (shared with
    /// the model: walls never change).
    pub terrains: Vec<(usize, Arc<floe_engine::terrain::HeightGrid>)>,
    /// Latest status.
    pub status: Mutex<Status>,
    /// Latest snapshot (latest-frame semantics: a receiver sees only the newest).
    pub published_state: watch::Sender<Option<Arc<Published>>>,
    /// Events.
    pub events: broadcast::Sender<Event>,
    /// Open frame streams, and how many of them asked for each channel and
    /// each position grid.
    pub subscribers: AtomicU32,
    /// Per (set, channel) and per (set, position grid): how many subscribers want it.
    wanted: Mutex<Wants>,
    /// Frames skipped by subscribers that went on to a later frame.
    dropped_frames: AtomicU64,
    /// Per live subscription, the sequence of the last snapshot it received (or
    /// the one it started at), so frames a blocked subscriber is missing count
    /// as dropped while it is blocked, not only once it reads again.
    delivered: Mutex<Vec<std::sync::Weak<AtomicU64>>>,
    /// Snapshots published.
    pub published: AtomicU64,
    /// Encoded frame bytes sent to subscribers (counted by the transports).
    pub frame_bytes: AtomicU64,
    /// Backend time per pass so far (label, seconds, calls), refreshed after every step.
    pub passes: Mutex<Vec<(&'static str, f64, u64)>>,
    /// Set on delete, so a long hand-step ends at the next step.
    pub(super) cancel: AtomicBool,
    /// The size the server chose for a preset created without a resolution
    /// ([`crate::sizing`]); none for a scene sized by its creator.
    sizing: std::sync::OnceLock<crate::sizing::Sizing>,
}

impl Shared {
    /// The size the server chose for the scene, where it did.
    pub fn sizing(&self) -> Option<&crate::sizing::Sizing> {
        self.sizing.get()
    }

    /// Records the size the server chose at creation.
    pub(super) fn sized(&self, sizing: crate::sizing::Sizing) {
        let _ = self.sizing.set(sizing);
    }

    /// The shared state of a scene's simulation (new or restored), paused.
    pub(super) fn new(id: u64, owner: String, sim: &Simulation) -> Self {
        let domain = sim.domain();
        let (published_state, _) = watch::channel(None);
        let (events, _) = broadcast::channel(16);
        Self {
            id,
            name: sim.scene().name.clone(),
            owner,
            scene_json: Mutex::new(serde_json::to_string(sim.scene()).expect("scenes serialise")),
            particles: sim.model().particle_capacity(),
            channels: scene_channels(sim.channels()),
            sets: sim
                .sets()
                .into_iter()
                .map(|(spec, count)| SceneSet {
                    name: spec.name,
                    count,
                    grid: spec.grid.is_some(),
                    look: spec.look.map(|l| l.name()),
                    surface: spec.surface,
                    shade: spec.shade,
                    part_of: spec.kind.map(|_| spec.channel_set()),
                })
                .collect(),
            tunables: floe_engine::module::tunables(sim.scene()),
            materials: Arc::new(sim.model().materials.clone()),
            particle_spacing: sim.scene().particle_spacing,
            backend: sim.backend_name(),
            bounds: (domain.min.to_array(), domain.max.to_array()),
            terrains: (sim.model().wall_constraints.iter().enumerate())
                .filter_map(|(i, w)| match w {
                    floe_engine::boundary::WallConstraint::Terrain(t) => Some((i, t.grid.clone())),
                    _ => None,
                })
                .collect(),
            status: Mutex::new(Status {
                state: if sim.halted().is_some() { State::Halted } else { State::Paused },
                time: sim.time(),
                steps: sim.steps(),
                dt: 0.0,
                steps_per_second: 0.0,
                halt_reason: sim.halted().map(|h| h.to_string()),
                measures: Vec::new(),
            }),
            published_state,
            events,
            subscribers: AtomicU32::new(0),
            wanted: Mutex::new((Tally::default(), Tally::default())),
            dropped_frames: AtomicU64::new(0),
            delivered: Mutex::new(Vec::new()),
            published: AtomicU64::new(0),
            frame_bytes: AtomicU64::new(0),
            passes: Mutex::new(sim.kernel_times()),
            cancel: AtomicBool::new(false),
            sizing: std::sync::OnceLock::new(),
        }
    }

    /// Registers a subscriber wanting `channels` of particle set `set` with positions
    /// quantised to `grid`; undone by [`Shared::unsubscribe`].
    pub fn subscribe(&self, set: u8, channels: &[&'static str], grid: PositionGrid) {
        self.subscribers.fetch_add(1, Ordering::Relaxed);
        let mut wanted = self.wanted.lock().expect("lock");
        channels.iter().for_each(|&c| wanted.0.add((set, c)));
        wanted.1.add((set, grid));
    }

    /// Removes a subscriber registered with `set`, `channels` and `grid`.
    pub fn unsubscribe(&self, set: u8, channels: &[&'static str], grid: PositionGrid) {
        self.subscribers.fetch_sub(1, Ordering::Relaxed);
        let mut wanted = self.wanted.lock().expect("lock");
        channels.iter().for_each(|&c| wanted.0.remove((set, c)));
        wanted.1.remove((set, grid));
    }

    /// Tracks a subscription's last received sequence (see [`Shared::dropped_frames`]).
    pub fn track(&self, last: &Arc<AtomicU64>) {
        let mut d = self.delivered.lock().expect("lock");
        d.retain(|w| w.strong_count() > 0);
        d.push(Arc::downgrade(last));
    }

    /// Records `n` frames a subscriber skipped.
    pub fn add_dropped(&self, n: u64) {
        self.dropped_frames.fetch_add(n, Ordering::Relaxed);
    }

    /// Frames skipped by subscribers so far: those skipped before a frame they
    /// received, plus those a subscriber is missing right now.
    pub fn dropped_frames(&self) -> u64 {
        let latest = self.published_state.borrow().as_ref().map_or(0, |s| s.sequence);
        let pending: u64 = self
            .delivered
            .lock()
            .expect("lock")
            .iter()
            .filter_map(|w| w.upgrade())
            .map(|last| latest.saturating_sub(last.load(Ordering::Relaxed)).saturating_sub(1))
            .sum();
        self.dropped_frames.load(Ordering::Relaxed) + pending
    }

    /// Per particle set someone subscribes to (set 0 always): the union of the
    /// channels its subscribers want (the only ones read back), and the position
    /// grid when every subscriber of the set quantises to the same one (positions are
    /// then quantised where they live: on a GPU, on the device).
    pub(super) fn wanted(&self) -> Vec<Wanted> {
        let wanted = self.wanted.lock().expect("lock");
        let mut sets: Vec<u8> = wanted.1.values().map(|(s, _)| s).collect();
        sets.push(0);
        sets.sort_unstable();
        sets.dedup();
        sets.into_iter()
            .map(|set| {
                let grids: Vec<PositionGrid> = wanted.1.values().filter(|(s, _)| *s == set).map(|(_, g)| g).collect();
                Wanted {
                    set,
                    channels: wanted.0.values().filter(|(s, _)| *s == set).map(|(_, c)| c).collect(),
                    grid: (grids.len() == 1).then(|| grids[0]),
                }
            })
            .collect()
    }

    /// The resolved scene as JSON, live changes included.
    pub fn scene_json(&self) -> String {
        self.scene_json.lock().expect("lock").clone()
    }

    /// A copy of the latest status.
    pub fn status(&self) -> Status {
        self.status.lock().expect("lock").clone()
    }
}

/// Subscribers per (set, channel) and per (set, position grid).
type Wants = (Tally<(u8, &'static str)>, Tally<(u8, PositionGrid)>);

/// What the subscribers of one particle set want read back.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Wanted {
    /// The set's index.
    pub set: u8,
    /// The channels any of its subscribers asked for.
    pub channels: Vec<&'static str>,
    /// The position grid, when all its subscribers share one.
    pub grid: Option<PositionGrid>,
}

/// A channel of a scene: what the engine declares, and its tag on the wire.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneChannel {
    /// Name, unit, components, set and owner.
    pub spec: ChannelSpec,
    /// The table's tag for a name it has, else one of the per-scene tags.
    pub kind: ChannelKind,
}

/// A particle set of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSet {
    /// Name (`particles`).
    pub name: &'static str,
    /// Particles (or cells) in it.
    pub count: usize,
    /// Whether it is a grid (its frames are grid frames).
    pub grid: bool,
    /// How viewers draw it (a material look's name), if the module says.
    pub look: Option<&'static str>,
    /// For a grid: the channel of its cells' surface heights (m), if any.
    pub surface: Option<&'static str>,
    /// For a grid in a look: the channel (0 to 1) scaling how much of the look is drawn.
    pub shade: Option<&'static str>,
    /// For a part of the SPH particles (the solid's, the fluid's): the set it is part
    /// of, whose channels it offers.
    pub part_of: Option<&'static str>,
}

impl SceneSet {
    /// The set whose channels it offers: the one it is part of, else its own.
    pub fn channel_set(&self) -> &'static str {
        self.part_of.unwrap_or(self.name)
    }
}

/// The wire tags of a scene's channels: the table's tag where `proto/channels.json`
/// names the channel, else the next free per-scene tag, in declaration order.
pub fn scene_channels(specs: Vec<ChannelSpec>) -> Vec<SceneChannel> {
    let mut dynamic = floe_proto::channels::DYNAMIC_TAGS;
    specs
        .into_iter()
        .map(|spec| {
            let kind = ChannelKind::named(spec.name)
                .unwrap_or_else(|| ChannelKind(dynamic.next().expect("fewer channels than per-scene tags (192)")));
            SceneChannel { spec, kind }
        })
        .collect()
}

/// How many open subscriptions want each value.
#[derive(Debug)]
struct Tally<T>(Vec<(T, u32)>);

impl<T> Default for Tally<T> {
    fn default() -> Self {
        Self(Vec::new())
    }
}

impl<T: PartialEq + Copy> Tally<T> {
    fn add(&mut self, v: T) {
        match self.0.iter_mut().find(|w| w.0 == v) {
            Some(w) => w.1 += 1,
            None => self.0.push((v, 1)),
        }
    }

    fn remove(&mut self, v: T) {
        if let Some(w) = self.0.iter_mut().find(|w| w.0 == v) {
            w.1 -= 1;
        }
        self.0.retain(|w| w.1 > 0);
    }

    fn values(&self) -> impl Iterator<Item = T> + '_ {
        self.0.iter().map(|w| w.0)
    }
}
