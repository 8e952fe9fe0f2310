//! The server's handle on one scene: commands go to the scene's worker thread
//! (see [`super::worker`]) as messages, so they are ordered with the stepping
//! and never race it; replies come back on oneshot channels.

use super::shared::{Shared, Status};
use super::worker::Worker;
use crate::cluster::Tenure;
use floe_engine::Simulation;
use floe_engine::quantize::PositionGrid;
use floe_engine::simulation::BackendFactory;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use tokio::sync::oneshot;

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
    /// A step request asks for more steps than one request may take.
    #[error("{0}")]
    TooFar(String),
}

/// A request to a scene's worker.
pub(super) enum Command {
    Step {
        steps: u64,
        until: Option<f64>,
        /// The steps taken when the caller gave up ([`STILL_HERE`] until then): the
        /// worker stops at the next step boundary.
        abandoned: Arc<AtomicU64>,
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
        reply: oneshot::Sender<Saved>,
    },
    Restore {
        state: Vec<u8>,
        reply: oneshot::Sender<Result<Status, CommandError>>,
    },
    Delete,
}

/// A scene's complete state and where it was taken.
#[derive(Debug)]
pub struct Saved {
    /// The snapshot (see `floe_engine::snapshot`).
    pub state: Vec<u8>,
    /// Steps taken.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
}

/// What [`Command::Step`]'s `abandoned` holds while its caller is still there.
pub(super) const STILL_HERE: u64 = u64::MAX;

/// Records the scene's step count when dropped: a step call's future dropped by a
/// transport whose client went away (a cancelled call, a deadline, a closed
/// connection) stops the stepping at the next step boundary.
struct Abandon {
    left: Arc<AtomicU64>,
    shared: Arc<Shared>,
}

impl Drop for Abandon {
    fn drop(&mut self) {
        self.left.store(self.shared.status().steps, Ordering::SeqCst);
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

/// Most steps one `step` request may ask for (`steps`), or that reaching its
/// `until_time` may take: a time farther ahead than this many of the scene's
/// largest steps is refused, naming the latest time one request may reach.
pub const MAX_STEPS_PER_REQUEST: u64 = 1_000_000;

impl SceneHandle {
    /// Starts the worker of a built (or restored) simulation owned by `owner`, which
    /// steps only while `tenure` holds.
    pub fn spawn(id: u64, owner: String, sim: Simulation, backend: Arc<BackendFactory>, tenure: Arc<Tenure>) -> Self {
        let shared = Arc::new(Shared::new(id, owner, &sim));
        let (tx, rx) = mpsc::channel();
        let worker_shared = shared.clone();
        let worker = std::thread::Builder::new()
            .name(format!("scene-{id}"))
            .spawn(move || Worker::new(sim, backend, worker_shared, tenure).run(rx))
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

    /// Steps a paused scene `steps` times, or until simulated time `until` (s) but
    /// at most [`MAX_STEPS_PER_REQUEST`] steps (an `until` farther ahead than that
    /// many of the scene's largest steps is refused). Dropping the future (the caller
    /// went away: a cancelled call, a closed connection) stops the stepping at the
    /// next step boundary, leaving the scene paused there.
    pub async fn step(&self, steps: u64, until: Option<f64>) -> Result<Status, CommandError> {
        let abandon = Abandon { left: Arc::new(AtomicU64::new(STILL_HERE)), shared: self.shared.clone() };
        let abandoned = abandon.left.clone();
        self.request(|reply| Command::Step { steps, until, abandoned, reply }).await?
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
        Ok(self.save_at().await?.state)
    }

    /// The scene's complete state with the step and time it was taken at.
    pub async fn save_at(&self) -> Result<Saved, CommandError> {
        self.request(|reply| Command::Save { reply }).await
    }

    /// Replaces a paused scene's state with a snapshot of the same scene.
    pub async fn restore(&self, state: Vec<u8>) -> Result<Status, CommandError> {
        self.request(|reply| Command::Restore { state, reply }).await?
    }

    /// Registers a frame subscriber wanting `channels` on `grid` and has the
    /// worker publish a fresh snapshot for it. Undo with [`Shared::unsubscribe`].
    pub fn subscribe(&self, set: u8, channels: &[&'static str], grid: PositionGrid) {
        self.shared.subscribe(set, channels, grid);
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
