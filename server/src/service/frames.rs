//! Frame subscriptions: turn a scene's latest published states into encoded frames at a
//! subscriber's rate and options, with latest-frame semantics.
//!
//! A subscriber that reads slowly only ever waits for the newest snapshot (a
//! `watch` channel holds one), so the solver never waits and memory never grows;
//! the snapshots it missed are counted as dropped. Unordered frames with the same
//! options are encoded once per snapshot and shared by every subscriber; an
//! identity-ordered stream predicts from the frames its own subscriber received,
//! so it has an encoder of its own.

use super::ServiceError;
use super::handle::SceneHandle;
use super::options::FrameOptions;
use super::shared::{Published, Shared, State};
use super::view::{View, ViewRequest};
use floe_engine::quantize::PositionGrid;
use floe_proto::{Bounds, EncodeError, Encoder, EncoderConfig, FrameInput, Mode, Particles};
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::watch;

/// One frame for one subscriber.
#[derive(Debug, Clone)]
pub struct EncodedFrame {
    /// The encoded bytes (shared between subscribers with the same options).
    pub data: Arc<Vec<u8>>,
    /// Snapshot sequence number.
    pub sequence: u64,
    /// Snapshots skipped since this subscriber's previous frame.
    pub skipped: u64,
}

/// Shared unordered encoders of one scene, one per distinct option set.
#[derive(Debug, Default)]
pub struct FrameCache {
    entries: Mutex<Vec<CacheEntry>>,
}

#[derive(Debug)]
struct CacheEntry {
    options: FrameOptions,
    encoder: Encoder,
    last: Option<(u64, Arc<Vec<u8>>)>,
}

fn config(shared: &Shared, o: &FrameOptions) -> EncoderConfig {
    let bounds = Bounds { min: shared.bounds.0, max: shared.bounds.1 };
    let mut c = EncoderConfig::new(o.mode, shared.id, bounds);
    c.position_bits = o.position_bits;
    c
}

/// The position grid of an encoder: the points the worker may snap positions
/// to without changing a single code of this stream.
fn position_grid(c: &EncoderConfig) -> PositionGrid {
    let q = c.position_quantizers();
    PositionGrid { min: q.map(|q| q.min), max: q.map(|q| q.max), bits: q[0].bits }
}

/// The frame input of `p`'s channels `channels`, under their tags in `shared`.
fn input<'a>(shared: &Shared, p: &'a Particles, o: &FrameOptions) -> FrameInput<'a> {
    let channels = o
        .channels
        .iter()
        .filter_map(|&name| {
            let kind = shared.channels.iter().find(|c| c.spec.name == name)?.kind;
            Some((kind, p.channel(name)?.as_ref()))
        })
        .collect();
    // Identity-ordered frames name their particles where the ids are not 0 .. n.
    let ids = p.ids.as_deref().filter(|_| o.mode == floe_proto::Mode::IdentityOrdered);
    FrameInput { positions: &p.positions, grid: p.grid, set: o.set, channels, ids }
}

/// Encodes published state `s` with `o`'s set, channels and decimation, or the
/// particles `view` keeps (`s` holds the set: a subscription waits for a state read
/// after it subscribed).
fn encode(
    encoder: &mut Encoder,
    shared: &Shared,
    s: &Published,
    o: &FrameOptions,
    view: Option<&View>,
) -> Result<Vec<u8>, EncodeError> {
    let particles = s.particles(o.set).expect("published states hold the subscribers' sets");
    if let Some(v) = view {
        encoder.encode(s.step, s.time, &input(shared, &v.apply(particles), o))
    } else if o.decimation > 1 {
        encoder.encode(s.step, s.time, &input(shared, &particles.every(o.decimation as usize), o))
    } else {
        encoder.encode(s.step, s.time, &input(shared, particles, o))
    }
}

impl FrameCache {
    /// The unordered frame of `snapshot` for `options`, encoding it on first request.
    fn unordered(&self, shared: &Shared, options: &FrameOptions, s: &Published) -> Result<Arc<Vec<u8>>, EncodeError> {
        let mut entries = self.entries.lock().expect("lock");
        let k = match entries.iter().position(|e| &e.options == options) {
            Some(k) => k,
            None => {
                entries.push(CacheEntry {
                    options: options.clone(),
                    encoder: Encoder::new(config(shared, options))?,
                    last: None,
                });
                entries.len() - 1
            }
        };
        let e = &mut entries[k];
        if let Some((seq, data)) = &e.last
            && *seq == s.sequence
        {
            return Ok(data.clone());
        }
        let data = Arc::new(encode(&mut e.encoder, shared, s, options, None)?);
        e.last = Some((s.sequence, data.clone()));
        Ok(data)
    }
}

/// A subscriber's stream of frames. Dropping it unsubscribes.
#[derive(Debug)]
pub struct Subscription {
    scene: Arc<SceneHandle>,
    cache: Arc<FrameCache>,
    rx: watch::Receiver<Option<Arc<Published>>>,
    options: FrameOptions,
    /// The grid this stream's encoder quantises positions to.
    grid: PositionGrid,
    own: Option<Encoder>,
    /// The region of interest and budget, which the stream's client may change.
    view: watch::Receiver<Option<View>>,
    view_control: ViewControl,
    last_sequence: Option<u64>,
    /// `last_sequence` shared with the scene's dropped-frame count.
    delivered: Arc<std::sync::atomic::AtomicU64>,
    last_sent: Option<Instant>,
}

impl Subscription {
    /// Subscribes to `scene`'s frames.
    pub fn new(
        scene: Arc<SceneHandle>,
        cache: Arc<FrameCache>,
        mut options: FrameOptions,
    ) -> Result<Self, EncodeError> {
        let own = match options.mode {
            Mode::IdentityOrdered => Some(Encoder::new(config(&scene.shared, &options))?),
            Mode::Unordered | Mode::Grid => {
                // Checks the options now rather than at the first frame.
                Encoder::new(config(&scene.shared, &options))?;
                None
            }
        };
        let mut rx = scene.shared.published_state.subscribe();
        // The snapshot held now may be stale (nobody was subscribed while the scene
        // stepped): treat it as seen, and have the worker publish a fresh one.
        let last_sequence = rx.borrow_and_update().as_ref().map(|s| s.sequence);
        // The fresh snapshot the worker publishes next is this subscriber's first.
        let delivered = Arc::new(std::sync::atomic::AtomicU64::new(last_sequence.unwrap_or(0)));
        scene.shared.track(&delivered);
        let grid = position_grid(&config(&scene.shared, &options));
        scene.subscribe(options.set, &options.channels, grid);
        let (tx, view) = watch::channel(options.view.take());
        let view_control =
            ViewControl { tx: Arc::new(tx), options: options.clone(), set: set_name(&scene.shared, &options) };
        Ok(Self { scene, cache, rx, options, grid, own, view, view_control, last_sequence, delivered, last_sent: None })
    }

    /// What changes this stream's region of interest while it is open.
    pub fn view_control(&self) -> ViewControl {
        self.view_control.clone()
    }

    /// The next frame; `None` once the scene is gone.
    pub async fn next(&mut self) -> Option<Result<EncodedFrame, EncodeError>> {
        if let Some(t) = self.last_sent {
            let gap = Duration::from_secs_f64(1.0 / self.options.max_fps);
            tokio::time::sleep_until((t + gap).into()).await;
        }
        // Whether the view changed since the last frame: the state sent last then comes again
        // as the new view shows it (a paused scene's camera moved). Before the first frame
        // there is nothing to send again: the first is of the latest view anyway.
        let mut moved = false;
        loop {
            if self.scene.shared.status().state == State::Deleted {
                return None;
            }
            let fresh = self.rx.borrow_and_update().clone();
            moved |= self.view.has_changed().unwrap_or(false);
            if moved && self.last_sent.is_none() {
                self.view.borrow_and_update();
                moved = false;
            }
            match fresh {
                Some(s)
                    if (moved || self.last_sequence.is_none_or(|l| s.sequence > l))
                        && s.particles(self.options.set).is_some() =>
                {
                    return Some(self.encode(s).await);
                }
                _ => {
                    tokio::select! {
                        changed = self.rx.changed() => if changed.is_err() {
                            return None;
                        },
                        // (The sender is this subscription's own, `view_control`: never gone.
                        // `changed` marks the view seen, hence the flag.)
                        _ = self.view.changed() => moved = true,
                    }
                }
            }
        }
    }

    async fn encode(&mut self, s: Arc<Published>) -> Result<EncodedFrame, EncodeError> {
        // (A state sent again for a new view skipped nothing.)
        let skipped = self.last_sequence.map_or(0, |l| s.sequence.saturating_sub(l + 1));
        // The first frame's predecessor was never sent to this subscriber.
        let skipped = if self.last_sent.is_none() { 0 } else { skipped };
        self.scene.shared.add_dropped(skipped);
        self.last_sequence = Some(s.sequence);
        self.delivered.store(s.sequence, Ordering::Relaxed);
        self.last_sent = Some(Instant::now());
        let sequence = s.sequence;
        let view = self.view.borrow_and_update().clone();
        // A view is this subscriber's own: its frames have an encoder of their own.
        if view.is_some() && self.own.is_none() {
            self.own = Some(Encoder::new(config(&self.scene.shared, &self.options))?);
        }
        if view.is_none() && self.options.mode != Mode::IdentityOrdered {
            self.own = None;
        }
        // Encoding a large frame takes milliseconds: keep it off the async workers.
        let data = match self.own.take() {
            Some(mut enc) => {
                let (options, scene) = (self.options.clone(), self.scene.clone());
                let (enc, data) = tokio::task::spawn_blocking(move || {
                    let data = encode(&mut enc, &scene.shared, &s, &options, view.as_ref());
                    (enc, data)
                })
                .await
                .expect("encoder task");
                self.own = Some(enc);
                Arc::new(data?)
            }
            None => {
                let (cache, scene, options) = (self.cache.clone(), self.scene.clone(), self.options.clone());
                tokio::task::spawn_blocking(move || cache.unordered(&scene.shared, &options, &s))
                    .await
                    .expect("encoder task")?
            }
        };
        Ok(EncodedFrame { data, sequence, skipped })
    }
}

/// The name of the set `o` streams.
fn set_name(shared: &Shared, o: &FrameOptions) -> String {
    shared.sets.get(usize::from(o.set)).map_or_else(String::new, |s| s.name.to_string())
}

/// Changes a stream's region of interest and budget while it is open (a WebSocket's
/// `view` message, a gRPC stream's next request): the next frame is of the new view.
#[derive(Debug, Clone)]
pub struct ViewControl {
    tx: Arc<watch::Sender<Option<View>>>,
    options: FrameOptions,
    set: String,
}

impl ViewControl {
    /// Checks `request` against the stream's options and makes it the stream's view
    /// (an empty request: every particle again).
    pub fn set(&self, request: &ViewRequest) -> Result<(), ServiceError> {
        let view = self.options.check_view(request, &self.set)?;
        self.tx.send_replace(view);
        Ok(())
    }
}

impl Drop for Subscription {
    fn drop(&mut self) {
        self.scene.shared.unsubscribe(self.options.set, &self.options.channels, self.grid);
    }
}
