//! A scene's worker thread: it owns the simulation, carries out commands in
//! order, steps (by hand or continuously, paced to a real-time factor) and
//! publishes particle state for frame subscribers.

use super::handle::{Command, CommandError, MAX_STEPS_PER_REQUEST, STILL_HERE, Saved};
use super::shared::{Event, Published, Shared, State, Status};
use crate::cluster::Tenure;
use floe_engine::simulation::BackendFactory;
use floe_engine::{Halted, Simulation};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Snapshots are published at most this often while stepping (s of wall time).
const PUBLISH_INTERVAL: Duration = Duration::from_millis(16);

/// Measures are refreshed at most this often while running (they may read state back).
const MEASURE_INTERVAL: Duration = Duration::from_millis(500);

/// The worker thread's state.
pub(super) struct Worker {
    sim: Simulation,
    /// Builds the backend of a reset or restored simulation.
    backend: Arc<BackendFactory>,
    shared: Arc<Shared>,
    /// Stepping stops while it does not hold (a cluster worker that may have lost
    /// its scenes); always held on a single server.
    tenure: Arc<Tenure>,
    running: Option<f64>,
    last_publish: Option<Instant>,
    last_measure: Option<Instant>,
    sequence: u64,
    rate: (Instant, u64),
}

impl Worker {
    pub(super) fn new(sim: Simulation, backend: Arc<BackendFactory>, shared: Arc<Shared>, tenure: Arc<Tenure>) -> Self {
        Self {
            sim,
            backend,
            shared,
            tenure,
            running: None,
            last_publish: None,
            last_measure: None,
            sequence: 0,
            rate: (Instant::now(), 0),
        }
    }

    pub(super) fn run(mut self, rx: mpsc::Receiver<Command>) {
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
                    let (step, time) = (self.sim.steps(), self.sim.time());
                    let _ = reply.send(Saved { state: self.sim.snapshot(), step, time });
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
                Some(Command::Step { steps, until, abandoned, reply }) => {
                    let r = if self.running.is_some() {
                        Err(CommandError::Running)
                    } else {
                        self.refuse_if_halted().and_then(|_| self.reachable(until)).map(|_| {
                            self.step_by_hand(steps, until, &abandoned);
                            self.shared.status()
                        })
                    };
                    let _ = reply.send(r);
                }
                None => {}
            }
            if let Some(rtf) = self.running {
                if !self.tenure.holds() {
                    std::thread::sleep(Duration::from_millis(10));
                    continue;
                }
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
        // The event first: whoever sees the Deleted state can find the event already sent.
        let _ = self.shared.events.send(Event::Deleted);
        self.set_state(State::Deleted);
        // Wakes frame subscribers waiting for a snapshot, so they see the deletion.
        self.shared.published_state.send_replace(None);
    }

    fn restore(&mut self, state: &[u8]) -> Result<Status, CommandError> {
        // Checked before anything is built: a snapshot of another (maybe far larger)
        // scene allocates nothing.
        let scene = Simulation::snapshot_scene(state).map_err(|e| CommandError::BadSnapshot(e.to_string()))?;
        if &scene != self.sim.scene() {
            return Err(CommandError::BadSnapshot("the snapshot is of a different scene".into()));
        }
        let sim =
            Simulation::restore_on(state, &*self.backend).map_err(|e| CommandError::BadSnapshot(e.to_string()))?;
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

    /// Refuses an `until` (s) farther ahead than [`MAX_STEPS_PER_REQUEST`] of the
    /// scene's largest steps: it would take more steps than one request may.
    fn reachable(&self, until: Option<f64>) -> Result<(), CommandError> {
        let Some(t) = until else { return Ok(()) };
        let (now, largest) = (self.sim.time(), self.sim.largest_step());
        let latest = now + largest * MAX_STEPS_PER_REQUEST as f64;
        if t <= latest {
            return Ok(());
        }
        // Six significant digits, rounded down so that the time offered is within reach.
        let digits = 10f64.powi(5 - latest.abs().log10().floor() as i32);
        let offer = (latest * digits).floor() / digits;
        Err(CommandError::TooFar(format!(
            "until_time: {t} s is more than {MAX_STEPS_PER_REQUEST} steps ahead of t = {now} s (steps are at most \
             {} s), more than one request may take; ask for at most {offer} s, or run the scene",
            largest as f32
        )))
    }

    /// Steps `steps` times, or until `until` but at most [`MAX_STEPS_PER_REQUEST`]
    /// steps; stops early when the scene is deleted or the caller is gone. A step is
    /// not interrupted half-way (its passes update the state in place: a state between
    /// two of them is none a frame, a snapshot or the next step could start from), so
    /// a caller who leaves gets the step under way finished and no other started; the
    /// scene's watchers are told ([`Event::StepAbandoned`]).
    fn step_by_hand(&mut self, steps: u64, until: Option<f64>, abandoned: &AtomicU64) {
        let mut taken = 0;
        loop {
            let done = match until {
                Some(t) => self.sim.time() >= t || taken >= MAX_STEPS_PER_REQUEST,
                None => taken >= steps,
            };
            let left_at = abandoned.load(Ordering::SeqCst);
            if left_at != STILL_HERE {
                let stopped_at = self.sim.steps();
                tracing::info!(
                    scene = self.shared.id,
                    "a step call's caller left at step {left_at}; stopped at step {stopped_at}"
                );
                let _ = self.shared.events.send(Event::StepAbandoned { left_at, stopped_at });
                break;
            }
            let stop = self.shared.cancel.load(Ordering::Relaxed) || !self.tenure.holds();
            if done || stop || !self.step_once() {
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
                *self.shared.passes.lock().expect("lock") = self.sim.kernel_times();
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

    /// Refreshes the status's measures: always when stepping has stopped, at most every
    /// [`MEASURE_INTERVAL`] while running.
    fn measure(&mut self) {
        if self.running.is_some() && self.last_measure.is_some_and(|t| t.elapsed() < MEASURE_INTERVAL) {
            return;
        }
        self.last_measure = Some(Instant::now());
        if let Ok(measures) = self.guarded(|sim| sim.measures()) {
            self.shared.status.lock().expect("lock").measures = measures;
        }
    }

    /// Publishes a snapshot of positions and the channels subscribers want; none
    /// is read back while nobody subscribes.
    fn publish(&mut self) {
        self.last_publish = Some(Instant::now());
        self.measure();
        if self.shared.subscribers.load(Ordering::Relaxed) == 0 && self.sequence > 0 {
            return;
        }
        let wanted = self.shared.wanted();
        let sets = self.sim.model().sets.clone();
        let read = self.guarded(|sim| {
            wanted
                .iter()
                .filter_map(|w| {
                    let spec = sets.get(usize::from(w.set))?;
                    let p = match w.grid {
                        Some(grid) => sim.read_on_grid(spec, &w.channels, &grid),
                        None => sim.read_set(spec, &w.channels),
                    };
                    Some((w.set, p))
                })
                .collect()
        });
        let sets = match read {
            Ok(p) => p,
            Err(h) => return self.report_halt(h),
        };
        let snapshot = Published { sequence: self.sequence, step: self.sim.steps(), time: self.sim.time(), sets };
        self.sequence += 1;
        self.shared.published.fetch_add(1, Ordering::Relaxed);
        self.shared.published_state.send_replace(Some(Arc::new(snapshot)));
    }
}
