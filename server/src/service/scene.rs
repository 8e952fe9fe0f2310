//! One scene on the server: its simulation lives on a worker thread of its own,
//! so stepping never blocks the async runtime, and talks to the rest of the
//! server through a command channel, a latest-snapshot watch and an event
//! broadcast.

use floe_engine::quantize::PositionGrid;
use floe_engine::simulation::BackendFactory;
use floe_engine::{Channel, Halted, Particles, Simulation};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, oneshot, watch};

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
}

/// Particle state published for frame subscribers, in identity order.
#[derive(Debug)]
pub struct Snapshot {
    /// Counts up by one per published snapshot.
    pub sequence: u64,
    /// Step it was taken at.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Positions and the channels subscribers asked for.
    pub particles: Particles,
}

/// Something that happened to a scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// The stability guard stopped it.
    Halted(floe_engine::Halted),
    /// Tunable settings changed (the overrides applied).
    ParameterChanged(Vec<String>),
    /// It was deleted.
    Deleted,
}

/// Why a command was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CommandError {
    /// The scene was halted by the guard and cannot step.
    #[error("scene is halted: {0}")]
    Halted(String),
    /// The scene is running; pause it first.
    #[error("scene is running; pause it before stepping it by hand")]
    Running,
    /// The worker is gone (the scene was deleted).
    #[error("scene was deleted")]
    Gone,
    /// A snapshot could not be restored into this scene.
    #[error("state: {0}")]
    BadSnapshot(String),
    /// A parameter change was refused; the message names the field.
    #[error("{0}")]
    BadParameter(String),
}

/// A request to a scene's worker.
enum Command {
    Step {
        steps: u64,
        until: Option<f64>,
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Run {
        real_time_factor: f64,
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Pause {
        reply: oneshot::Sender<Status>,
    },
    /// A subscriber joined: publish a fresh snapshot even if paused.
    Publish,
    Set {
        overrides: Vec<String>,
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Reset {
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Save {
        reply: oneshot::Sender<Vec<u8>>,
    },
    Restore {
        state: Vec<u8>,
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Delete,
}

/// State shared between a scene's worker and the server's tasks.
#[derive(Debug)]
pub struct Shared {
    /// Scene id.
    pub id: u64,
    /// Scene name.
    pub name: String,
    /// The resolved scene as JSON, as it is now (live changes included).
    scene_json: Mutex<String>,
    /// Fluid particles.
    pub particles: usize,
    /// Particle spacing (m).
    pub particle_spacing: f32,
    /// The backend stepping the scene (`gpu`, `cpu`); resets and restores keep it.
    pub backend: &'static str,
    /// Domain (m): frames quantise positions over it.
    pub bounds: ([f32; 3], [f32; 3]),
    /// Latest status.
    pub status: Mutex<Status>,
    /// Latest snapshot (latest-frame semantics: a receiver sees only the newest).
    pub snapshots: watch::Sender<Option<Arc<Snapshot>>>,
    /// Events.
    pub events: broadcast::Sender<Event>,
    /// Open frame streams, and how many of them asked for each channel and
    /// each position grid.
    pub subscribers: AtomicU32,
    wanted: Mutex<(Tally<Channel>, Tally<PositionGrid>)>,
    /// Frames skipped by subscribers that went on to a later frame.
    dropped_frames: AtomicU64,
    /// Per live subscription, the sequence of the last snapshot it received (or
    /// the one it started at), so frames a blocked subscriber is missing count
    /// as dropped while it is blocked, not only once it reads again.
    delivered: Mutex<Vec<std::sync::Weak<AtomicU64>>>,
    /// Snapshots published.
    pub published: AtomicU64,
    /// Set on delete, so a long hand-step ends at the next step.
    cancel: std::sync::atomic::AtomicBool,
}

impl Shared {
    /// Registers a subscriber wanting `channels` with positions quantised to
    /// `grid`; undone by [`Shared::unsubscribe`].
    pub fn subscribe(&self, channels: &[Channel], grid: PositionGrid) {
        self.subscribers.fetch_add(1, Ordering::Relaxed);
        let mut wanted = self.wanted.lock().expect("lock");
        channels.iter().for_each(|&c| wanted.0.add(c));
        wanted.1.add(grid);
    }

    /// Removes a subscriber registered with `channels` and `grid`.
    pub fn unsubscribe(&self, channels: &[Channel], grid: PositionGrid) {
        self.subscribers.fetch_sub(1, Ordering::Relaxed);
        let mut wanted = self.wanted.lock().expect("lock");
        channels.iter().for_each(|&c| wanted.0.remove(c));
        wanted.1.remove(grid);
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
        let latest = self.snapshots.borrow().as_ref().map_or(0, |s| s.sequence);
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

    /// The union of the channels subscribers want (the only ones read back),
    /// and the position grid when every subscriber quantises to the same one
    /// (positions are then quantised where they live: on a GPU, on the device).
    fn wanted(&self) -> (Vec<Channel>, Option<PositionGrid>) {
        let wanted = self.wanted.lock().expect("lock");
        let grids: Vec<PositionGrid> = wanted.1.values().collect();
        (wanted.0.values().collect(), (grids.len() == 1).then(|| grids[0]))
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

/// The server's handle on a scene.
#[derive(Debug)]
pub struct SceneHandle {
    /// Shared state.
    pub shared: Arc<Shared>,
    commands: Mutex<mpsc::Sender<Command>>,
    worker: Mutex<Option<std::thread::JoinHandle<()>>>,
}

/// Most steps one `step` request may ask for.
pub const MAX_STEPS_PER_REQUEST: u64 = 1_000_000;

/// Snapshots are published at most this often while stepping (s of wall time).
const PUBLISH_INTERVAL: Duration = Duration::from_millis(16);

impl SceneHandle {
    /// Starts the worker of a built simulation.
    pub fn spawn(id: u64, sim: Simulation, backend: Arc<BackendFactory>) -> Self {
        let domain = sim.domain();
        let (snapshots, _) = watch::channel(None);
        let (events, _) = broadcast::channel(16);
        let shared = Arc::new(Shared {
            id,
            name: sim.scene().name.clone(),
            scene_json: Mutex::new(serde_json::to_string(sim.scene()).expect("scenes serialise")),
            particles: sim.particle_count(),
            particle_spacing: sim.scene().particle_spacing,
            backend: sim.backend_name(),
            bounds: (domain.min.to_array(), domain.max.to_array()),
            status: Mutex::new(Status {
                state: State::Paused,
                time: 0.0,
                steps: 0,
                dt: 0.0,
                steps_per_second: 0.0,
                halt_reason: None,
            }),
            snapshots,
            events,
            subscribers: AtomicU32::new(0),
            wanted: Mutex::new((Tally::default(), Tally::default())),
            dropped_frames: AtomicU64::new(0),
            delivered: Mutex::new(Vec::new()),
            published: AtomicU64::new(0),
            cancel: std::sync::atomic::AtomicBool::new(false),
        });
        let (tx, rx) = mpsc::channel();
        let worker_shared = shared.clone();
        let worker = std::thread::Builder::new()
            .name(format!("scene-{id}"))
            .spawn(move || Worker::new(sim, backend, worker_shared).run(rx))
            .expect("spawn scene worker");
        Self { shared, commands: Mutex::new(tx), worker: Mutex::new(Some(worker)) }
    }

    fn send(&self, c: Command) -> Result<(), CommandError> {
        self.commands.lock().expect("lock").send(c).map_err(|_| CommandError::Gone)
    }

    /// Sends the command `make` builds around a reply channel and waits for the reply.
    async fn request<T>(&self, make: impl FnOnce(oneshot::Sender<T>) -> Command) -> Result<T, CommandError> {
        let (reply, rx) = oneshot::channel();
        self.send(make(reply))?;
        rx.await.map_err(|_| CommandError::Gone)
    }

    /// Steps a paused scene `steps` times, or until simulated time `until` (s).
    pub async fn step(&self, steps: u64, until: Option<f64>) -> Result<Status, CommandError> {
        self.request(|reply| Command::Step { steps, until, reply }).await?
    }

    /// Runs continuously at `real_time_factor` (0: as fast as possible).
    pub async fn run(&self, real_time_factor: f64) -> Result<Status, CommandError> {
        self.request(|reply| Command::Run { real_time_factor, reply }).await?
    }

    /// Pauses after the current step.
    pub async fn pause(&self) -> Result<Status, CommandError> {
        self.request(|reply| Command::Pause { reply }).await
    }

    /// Changes tunable settings (`key=value` overrides) from the next step on.
    pub async fn set_parameters(&self, overrides: Vec<String>) -> Result<Status, CommandError> {
        self.request(|reply| Command::Set { overrides, reply }).await?
    }

    /// Puts a paused (or halted) scene back at t = 0, keeping its current settings.
    pub async fn reset(&self) -> Result<Status, CommandError> {
        self.request(|reply| Command::Reset { reply }).await?
    }

    /// The scene's complete state (see `floe_engine::snapshot`).
    pub async fn save(&self) -> Result<Vec<u8>, CommandError> {
        self.request(|reply| Command::Save { reply }).await
    }

    /// Replaces a paused scene's state with a snapshot of the same scene.
    pub async fn restore(&self, state: Vec<u8>) -> Result<Status, CommandError> {
        self.request(|reply| Command::Restore { state, reply }).await?
    }

    /// Registers a frame subscriber wanting `channels` on `grid` and has the
    /// worker publish a fresh snapshot for it. Undo with [`Shared::unsubscribe`].
    pub fn subscribe(&self, channels: &[Channel], grid: PositionGrid) {
        self.shared.subscribe(channels, grid);
        let _ = self.send(Command::Publish);
    }

    /// Stops the worker and waits for it; streams see a Deleted event.
    pub fn delete(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
        let _ = self.send(Command::Delete);
        if let Some(w) = self.worker.lock().expect("lock").take() {
            let _ = w.join();
        }
    }
}

/// The worker thread's state.
struct Worker {
    sim: Simulation,
    /// Builds the backend of a reset or restored simulation.
    backend: Arc<BackendFactory>,
    shared: Arc<Shared>,
    running: Option<f64>,
    last_publish: Option<Instant>,
    sequence: u64,
    rate: (Instant, u64),
}

impl Worker {
    fn new(sim: Simulation, backend: Arc<BackendFactory>, shared: Arc<Shared>) -> Self {
        Self { sim, backend, shared, running: None, last_publish: None, sequence: 0, rate: (Instant::now(), 0) }
    }

    fn run(mut self, rx: mpsc::Receiver<Command>) {
        self.publish();
        let mut run_start = (Instant::now(), 0.0);
        loop {
            let command = if self.running.is_some() {
                match rx.try_recv() {
                    Ok(c) => Some(c),
                    Err(mpsc::TryRecvError::Empty) => None,
                    Err(mpsc::TryRecvError::Disconnected) => break,
                }
            } else {
                match rx.recv() {
                    Ok(c) => Some(c),
                    Err(_) => break,
                }
            };
            match command {
                Some(Command::Delete) => break,
                Some(Command::Publish) => self.publish(),
                Some(Command::Set { overrides, reply }) => {
                    let r = match self.sim.set_parameters(&overrides) {
                        Ok(()) => {
                            *self.shared.scene_json.lock().expect("lock") =
                                serde_json::to_string(self.sim.scene()).expect("scenes serialise");
                            tracing::info!(scene = self.shared.id, "parameters changed: {}", overrides.join(" "));
                            let _ = self.shared.events.send(Event::ParameterChanged(overrides));
                            Ok(self.shared.status())
                        }
                        Err(e) => Err(CommandError::BadParameter(e.to_string())),
                    };
                    let _ = reply.send(r);
                }
                Some(Command::Reset { reply }) => {
                    let r = if self.running.is_some() {
                        Err(CommandError::Running)
                    } else {
                        match Simulation::new(self.sim.scene().clone(), &*self.backend) {
                            Ok(sim) => Ok(self.replace(sim)),
                            Err(e) => Err(CommandError::BadParameter(e.to_string())),
                        }
                    };
                    let _ = reply.send(r);
                }
                Some(Command::Save { reply }) => {
                    let _ = reply.send(self.sim.snapshot());
                }
                Some(Command::Restore { state, reply }) => {
                    let r = if self.running.is_some() { Err(CommandError::Running) } else { self.restore(&state) };
                    let _ = reply.send(r);
                }
                Some(Command::Pause { reply }) => {
                    self.running = None;
                    self.set_state(State::Paused);
                    self.publish();
                    let _ = reply.send(self.shared.status());
                }
                Some(Command::Run { real_time_factor, reply }) => {
                    let r = self.refuse_if_halted();
                    if r.is_ok() {
                        self.running = Some(real_time_factor);
                        run_start = (Instant::now(), self.sim.time());
                        self.set_state(State::Running);
                    }
                    let _ = reply.send(r.map(|_| self.shared.status()));
                }
                Some(Command::Step { steps, until, reply }) => {
                    let r = if self.running.is_some() {
                        Err(CommandError::Running)
                    } else {
                        self.refuse_if_halted().map(|_| {
                            self.step_by_hand(steps, until);
                            self.shared.status()
                        })
                    };
                    let _ = reply.send(r);
                }
                None => {}
            }
            if let Some(rtf) = self.running {
                if rtf > 0.0 {
                    // Pace: sleep while simulated time is ahead of wall time * factor.
                    let ahead = (self.sim.time() - run_start.1) / rtf - run_start.0.elapsed().as_secs_f64();
                    if ahead > 0.0 {
                        std::thread::sleep(Duration::from_secs_f64(ahead.min(0.01)));
                        continue;
                    }
                }
                if !self.step_once() {
                    self.running = None;
                }
                self.publish_if_due();
            }
        }
        self.set_state(State::Deleted);
        let _ = self.shared.events.send(Event::Deleted);
        // Wakes frame subscribers waiting for a snapshot, so they see the deletion.
        self.shared.snapshots.send_replace(None);
    }

    fn restore(&mut self, state: &[u8]) -> Result<Status, CommandError> {
        let sim =
            Simulation::restore_on(state, &*self.backend).map_err(|e| CommandError::BadSnapshot(e.to_string()))?;
        if sim.scene() != self.sim.scene() {
            return Err(CommandError::BadSnapshot("the snapshot is of a different scene".into()));
        }
        Ok(self.replace(sim))
    }

    /// Takes `sim` as the scene's simulation and publishes its state.
    fn replace(&mut self, sim: Simulation) -> Status {
        self.sim = sim;
        {
            let mut s = self.shared.status.lock().expect("lock");
            s.time = self.sim.time();
            s.steps = self.sim.steps();
            s.halt_reason = self.sim.halted().map(|h| h.to_string());
            s.state = if s.halt_reason.is_some() { State::Halted } else { State::Paused };
        }
        self.publish();
        self.shared.status()
    }

    fn refuse_if_halted(&self) -> Result<(), CommandError> {
        match self.sim.halted() {
            Some(h) => Err(CommandError::Halted(h.to_string())),
            None => Ok(()),
        }
    }

    fn step_by_hand(&mut self, steps: u64, until: Option<f64>) {
        let mut taken = 0;
        loop {
            let done = match until {
                Some(t) => self.sim.time() >= t,
                None => taken >= steps,
            };
            if done || self.shared.cancel.load(Ordering::Relaxed) || !self.step_once() {
                break;
            }
            taken += 1;
            self.publish_if_due();
        }
        self.publish();
    }

    /// Runs `f` on the simulation; a panic in a backend (a bug, a lost GPU)
    /// halts this scene with the panic's message instead of killing its worker,
    /// so the scene still answers and every other scene goes on.
    fn guarded<T>(&mut self, f: impl FnOnce(&mut Simulation) -> T) -> Result<T, Halted> {
        let sim = &mut self.sim;
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(sim))).map_err(|panic| {
            let message = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("unknown panic");
            self.sim.fail(format!("internal error in the {} backend: {message}", self.sim.backend_name()))
        })
    }

    /// One step; on a halt, records it and tells subscribers. Returns whether it stepped.
    fn step_once(&mut self) -> bool {
        if self.sim.halted().is_some() {
            // Halted while publishing (see `guarded`): already reported.
            return false;
        }
        match self.guarded(Simulation::step).and_then(|r| r) {
            Ok(r) => {
                self.rate.1 += 1;
                let elapsed = self.rate.0.elapsed().as_secs_f64();
                let mut s = self.shared.status.lock().expect("lock");
                if elapsed >= 1.0 {
                    s.steps_per_second = self.rate.1 as f64 / elapsed;
                    self.rate = (Instant::now(), 0);
                }
                s.time = self.sim.time();
                s.steps = self.sim.steps();
                s.dt = r.dt as f64;
                true
            }
            Err(h) => {
                self.report_halt(h);
                self.publish();
                false
            }
        }
    }

    /// Shows a halt in the status and tells the event subscribers.
    fn report_halt(&self, h: Halted) {
        {
            let mut s = self.shared.status.lock().expect("lock");
            s.state = State::Halted;
            s.halt_reason = Some(h.to_string());
        }
        tracing::warn!(scene = self.shared.id, "{h}");
        let _ = self.shared.events.send(Event::Halted(h));
    }

    fn set_state(&self, state: State) {
        let mut s = self.shared.status.lock().expect("lock");
        if s.state != State::Halted || state == State::Deleted {
            s.state = state;
        }
    }

    fn publish_if_due(&mut self) {
        if self.last_publish.is_none_or(|t| t.elapsed() >= PUBLISH_INTERVAL) {
            self.publish();
        }
    }

    /// Publishes a snapshot of positions and the channels subscribers want; none
    /// is read back while nobody subscribes.
    fn publish(&mut self) {
        self.last_publish = Some(Instant::now());
        if self.shared.subscribers.load(Ordering::Relaxed) == 0 && self.sequence > 0 {
            return;
        }
        let wanted = self.shared.wanted();
        let read = self.guarded(|sim| match wanted {
            (channels, Some(grid)) => sim.read_on_grid(&channels, &grid),
            (channels, None) => sim.read(&channels),
        });
        let particles = match read {
            Ok(p) => p,
            Err(h) => return self.report_halt(h),
        };
        let snapshot = Snapshot { sequence: self.sequence, step: self.sim.steps(), time: self.sim.time(), particles };
        self.sequence += 1;
        self.shared.published.fetch_add(1, Ordering::Relaxed);
        self.shared.snapshots.send_replace(Some(Arc::new(snapshot)));
    }
}
