//! The WebSocket of a scene (`/api/v1/scenes/{id}/ws?channels=velocity&max_fps=30&bits=16&mode=unordered&decimation=1&set=particles&view={...}`):
//! binary messages carry encoded frames (latest-frame semantics, as over gRPC);
//! text messages are JSON both ways.
//!
//! A browser cannot set headers on a WebSocket: it offers its token as a protocol,
//! `new WebSocket(url, ["floe.v1", token])`, and the server answers `floe.v1`. The
//! handshake's Origin must be the server's own or one of `--allow-origin`
//! ([`crate::auth::origin`]).
//!
//! Client to server: `{"op": "run", "real_time_factor": 1}`, `{"op": "pause"}`,
//! `{"op": "step", "steps": 1}` (or `"until_time"`), `{"op": "set", "overrides": ["gravity=[0,-1,0]"]}`,
//! `{"op": "reset"}`, `{"op": "status"}`; the fields are those of the REST bodies and,
//! as there, unknown fields are refused. `{"op": "view", "box": {"min": [..], "max":
//! [..]}, "camera": {"position": [..], "direction": [..], "fov_deg": 60, "far": 100},
//! "budget": 200000}` changes the stream's region of interest and particle budget from
//! the next frame on (each part optional; none: every particle again;
//! [`crate::service::view`]); the query's `view` sets the first one, as JSON of the
//! same fields. Each counts against the request rate.
//! Server to client: `{"type": "status", "scene": {...}}` after each op,
//! `{"type": "event", "event": "halted", "reason": "...", "step": n, "sim_time": t}`,
//! `{"type": "event", "event": "deleted"}` (then the socket closes), and
//! `{"type": "error", "message": "..."}` for a message it could not use; the
//! connection stays open after an error. A message over 64 KiB closes the socket with
//! code 1009 and the reason.

use crate::auth::{Caller, WS_PROTOCOL, origin};
use crate::http::{ApiError, ParametersBody, Params, RunBody, SceneId, SceneView, StepBody, Who};
use crate::service::frames::{EncodedFrame, ViewControl};
use crate::service::options::FrameRequest;
use crate::service::view::ViewRequest;
use crate::service::{Event, Need, Registry, SceneHandle, ServiceError};
use axum::extract::State;
use axum::extract::ws::{CloseFrame, Message, WebSocket, WebSocketUpgrade, close_code};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::Response;
use serde::Deserialize;
use serde::de::DeserializeOwned;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, mpsc};

/// Largest message a client may send (bytes).
pub const MAX_MESSAGE_BYTES: usize = 64 << 10;
/// How often the server pings a quiet client, and how long it waits for any sign of it.
const PING_EVERY: Duration = Duration::from_secs(15);
const SILENCE_LIMIT: Duration = Duration::from_secs(45);

/// Query parameters of the socket.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WsQuery {
    /// Comma-separated channel names (the scene's info lists them).
    #[serde(default)]
    channels: String,
    /// Most frames per second (default 30).
    max_fps: Option<f64>,
    /// Bits per position axis (default 16).
    bits: Option<u8>,
    /// `unordered` (default) or `identity`.
    mode: Option<String>,
    /// Send every n-th particle (default 1: all).
    decimation: Option<u32>,
    /// The particle set (default `particles`).
    set: Option<String>,
    /// The region of interest and budget, as JSON (`{"box": ..., "camera": ..., "budget": n}`).
    view: Option<String>,
}

impl WsQuery {
    /// The frame options the query states (checked against the scene by the service).
    fn request(&self) -> Result<FrameRequest, ApiError> {
        let view = match self.view.as_deref().filter(|v| !v.trim().is_empty()) {
            None => ViewRequest::default(),
            Some(v) => serde_json::from_str(v).map_err(|e| {
                ApiError::new(StatusCode::BAD_REQUEST, format!("view: {}", crate::echo::bounded(&e.to_string())))
            })?,
        };
        Ok(FrameRequest {
            channels: self.channels.split(',').map(str::to_string).collect(),
            max_fps: self.max_fps,
            position_bits: self.bits.map(u32::from),
            mode: self.mode.clone(),
            decimation: self.decimation,
            set: self.set.clone(),
            view,
        })
    }
}

/// Upgrades to a WebSocket after checking the origin, the scene and the options.
pub async fn upgrade(
    State(registry): State<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
    Params(q): Params<WsQuery>,
    headers: HeaderMap,
    ws: WebSocketUpgrade,
) -> Result<Response, ApiError> {
    let text = |h| headers.get(h).and_then(|v: &axum::http::HeaderValue| v.to_str().ok());
    if !origin::allowed(text(header::ORIGIN), text(header::HOST), registry.access().origins()) {
        let o = crate::echo::cap(text(header::ORIGIN).unwrap_or_default());
        return Err(ApiError::new(
            StatusCode::FORBIDDEN,
            format!("origin {o} may not open a WebSocket here (the server's own origin or --allow-origin)"),
        ));
    }
    let handle = registry.get(&who, id, Need::Watch)?;
    let feed = registry.subscribe(&who, id, &q.request()?)?;
    let view = feed.view_control();
    let frames = feed.spawn(|frame| frame);
    let ws = ws.max_message_size(MAX_MESSAGE_BYTES).protocols([WS_PROTOCOL]);
    Ok(ws.on_upgrade(move |socket| session(socket, registry, who, handle, Stream { frames, view })))
}

fn json(value: serde_json::Value) -> Message {
    Message::Text(value.to_string().into())
}

fn error(message: &str) -> Message {
    json(serde_json::json!({ "type": "error", "message": crate::echo::bounded(message) }))
}

fn event_message(e: &Event) -> Message {
    match e {
        Event::Halted(h) => json(serde_json::json!({
            "type": "event", "event": "halted", "reason": h.to_string(), "step": h.step, "sim_time": h.time,
            "particle": h.particle,
        })),
        Event::ParameterChanged(o) => {
            json(serde_json::json!({ "type": "event", "event": "parameter_changed", "overrides": o }))
        }
        Event::StepAbandoned { left_at, stopped_at } => json(serde_json::json!({
            "type": "event", "event": "step_abandoned", "left_at_step": left_at, "stopped_at_step": stopped_at,
        })),
        Event::Deleted => json(serde_json::json!({ "type": "event", "event": "deleted" })),
    }
}

/// A control message from the client.
#[derive(Debug)]
pub(crate) enum Control {
    Run(RunBody),
    Pause,
    Step(StepBody),
    Set(ParametersBody),
    Reset,
    Status,
    View(ViewRequest),
}

/// Ops and whether they take fields (the REST body of the same call).
const OPS: &str = "run, pause, step, set, reset, status, view";

/// Reads a control message: `op` names the call, the other fields are its REST
/// body's, checked the same way (unknown fields refused).
pub(crate) fn parse_control(text: &str) -> Result<(Control, &'static str), String> {
    let mut fields: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(text).map_err(|e| format!("bad control message: {e}"))?;
    let op = match fields.remove("op") {
        Some(serde_json::Value::String(op)) => op,
        Some(_) => return Err("bad control message: op must be a string".into()),
        None => return Err(format!("bad control message: no op ({OPS})")),
    };
    fn body<T: DeserializeOwned>(op: &str, fields: serde_json::Map<String, serde_json::Value>) -> Result<T, String> {
        serde_json::from_value(serde_json::Value::Object(fields)).map_err(|e| format!("bad {op} message: {e}"))
    }
    let bare = |control: Control, name: &'static str| match fields.keys().next() {
        None => Ok((control, name)),
        Some(k) => Err(format!("bad {name} message: unknown field `{}`; {name} takes no fields", crate::echo::cap(k))),
    };
    match op.as_str() {
        "run" => Ok((Control::Run(body("run", fields)?), "run")),
        "step" => Ok((Control::Step(body("step", fields)?), "step")),
        "set" => Ok((Control::Set(body("set", fields)?), "set")),
        "view" => Ok((Control::View(body("view", fields)?), "view")),
        "pause" => bare(Control::Pause, "pause"),
        "reset" => bare(Control::Reset, "reset"),
        "status" => bare(Control::Status, "status"),
        other => Err(format!("bad control message: unknown op {:?} ({OPS})", crate::echo::cap(other))),
    }
}

/// Carries out a control message; the reply, and the label and code for the metrics.
async fn control(
    registry: &Registry,
    who: &Caller,
    handle: &SceneHandle,
    view: &ViewControl,
    text: &str,
) -> (Message, &'static str, String) {
    let (op, name) = match parse_control(text) {
        Ok(c) => c,
        Err(m) => return (error(&m), "invalid", "400".into()),
    };
    let id = handle.shared.id;
    let result: Result<(), ServiceError> = async {
        registry.admit(who)?;
        match op {
            Control::Run(b) => {
                let rtf = b.checked().map_err(ServiceError::InvalidArgument)?;
                registry.run(who, id, rtf).await?;
            }
            Control::Pause => {
                registry.pause(who, id).await?;
            }
            Control::Step(b) => {
                let (n, until) = b.checked().map_err(ServiceError::InvalidArgument)?;
                registry.step(who, id, n, until).await?;
            }
            Control::Set(b) => {
                registry.set_parameters(who, id, b.overrides).await?;
            }
            Control::Reset => {
                registry.reset(who, id).await?;
            }
            Control::Status => {}
            Control::View(v) => view.set(&v)?,
        }
        Ok(())
    }
    .await;
    match result {
        Ok(()) => (
            json(
                serde_json::json!({ "type": "status", "scene": SceneView::of(&handle.shared, registry.worker_name()) }),
            ),
            name,
            "200".into(),
        ),
        Err(e) => {
            let code = ApiError::from(e);
            (error(&code.message), name, code.status.as_str().to_owned())
        }
    }
}

/// Whether a receive error is a message over [`MAX_MESSAGE_BYTES`].
fn too_big(e: axum::Error) -> bool {
    matches!(
        e.into_inner().downcast::<tungstenite::Error>().map(|e| *e),
        Ok(tungstenite::Error::Capacity(tungstenite::error::CapacityError::MessageTooLong { .. }))
    )
}

/// What a session does after a message from its client.
enum Next {
    /// Goes on.
    Go,
    /// Closes, with this close frame if not the normal one.
    Close(Option<CloseFrame>),
}

/// One client's socket and what it streams.
struct Session {
    socket: WebSocket,
    registry: Arc<Registry>,
    who: Caller,
    handle: Arc<SceneHandle>,
    frames: mpsc::Receiver<Result<EncodedFrame, floe_proto::EncodeError>>,
    view: ViewControl,
    /// Messages that arrived while a control call ran, in order.
    waiting: std::collections::VecDeque<Message>,
    heard: Instant,
}

impl Session {
    /// Sends a frame (or the reason it could not be encoded); false once the client is gone.
    async fn forward(&mut self, frame: Option<Result<EncodedFrame, floe_proto::EncodeError>>) -> bool {
        match frame {
            Some(Ok(f)) => self.socket.send(Message::Binary(f.data.as_ref().clone().into())).await.is_ok(),
            Some(Err(e)) => {
                let _ = self.socket.send(error(&e.to_string())).await;
                true
            }
            None => false,
        }
    }

    /// Carries out a control message. While it runs (a step of many steps) frames
    /// still flow, and a client that leaves cancels it at the next step boundary
    /// (the call is dropped, as a cancelled gRPC call is); messages arriving
    /// meanwhile wait their turn.
    async fn call(&mut self, text: &str) -> Next {
        let t0 = Instant::now();
        let (registry, who, handle, view) =
            (self.registry.clone(), self.who.clone(), self.handle.clone(), self.view.clone());
        let call = control(&registry, &who, &handle, &view, text);
        tokio::pin!(call);
        let (reply, op, code) = loop {
            tokio::select! {
                done = &mut call => break done,
                frame = self.frames.recv() => {
                    if !self.forward(frame).await {
                        return Next::Close(None);
                    }
                }
                msg = self.socket.recv() => {
                    self.heard = Instant::now();
                    match msg {
                        Some(Ok(Message::Close(_))) | Some(Err(_)) | None => return Next::Close(None),
                        Some(Ok(m)) => self.waiting.push_back(m),
                    }
                }
            }
        };
        self.registry.metrics().observe("ws", op, &code, t0.elapsed().as_secs_f64());
        if self.socket.send(reply).await.is_err() { Next::Close(None) } else { Next::Go }
    }

    /// Handles one message from the client.
    async fn receive(&mut self, msg: Option<Result<Message, axum::Error>>) -> Next {
        match msg {
            Some(Ok(Message::Text(t))) => self.call(t.as_str()).await,
            Some(Ok(Message::Binary(_))) => {
                if self.socket.send(error("binary messages are not accepted; send JSON text")).await.is_err() {
                    return Next::Close(None);
                }
                Next::Go
            }
            Some(Err(e)) => Next::Close(too_big(e).then(|| {
                let reason = format!("message too big: at most {MAX_MESSAGE_BYTES} bytes");
                CloseFrame { code: close_code::SIZE, reason: reason.into() }
            })),
            Some(Ok(Message::Close(_))) | None => Next::Close(None),
            Some(Ok(_)) => Next::Go,
        }
    }
}

/// A socket's frames and what changes their view.
struct Stream {
    frames: mpsc::Receiver<Result<EncodedFrame, floe_proto::EncodeError>>,
    view: ViewControl,
}

async fn session(socket: WebSocket, registry: Arc<Registry>, who: Caller, handle: Arc<SceneHandle>, stream: Stream) {
    let mut events = handle.shared.events.subscribe();
    let mut s = Session {
        socket,
        registry,
        who,
        handle,
        frames: stream.frames,
        view: stream.view,
        waiting: std::collections::VecDeque::new(),
        heard: Instant::now(),
    };
    let hello = json(
        serde_json::json!({ "type": "status", "scene": SceneView::of(&s.handle.shared, s.registry.worker_name()) }),
    );
    if s.socket.send(hello).await.is_err() {
        return;
    }
    let mut ping = tokio::time::interval(PING_EVERY);
    let mut close: Option<CloseFrame> = None;
    loop {
        if let Some(m) = s.waiting.pop_front() {
            match s.receive(Some(Ok(m))).await {
                Next::Go => continue,
                Next::Close(c) => {
                    close = c;
                    break;
                }
            }
        }
        tokio::select! {
            frame = s.frames.recv() => {
                if !s.forward(frame).await {
                    break;
                }
            }
            msg = s.socket.recv() => {
                s.heard = Instant::now();
                if let Next::Close(c) = s.receive(msg).await {
                    close = c;
                    break;
                }
            },
            event = events.recv() => match event {
                Ok(e) => {
                    let last = e == Event::Deleted;
                    if s.socket.send(event_message(&e)).await.is_err() || last {
                        break;
                    }
                }
                Err(broadcast::error::RecvError::Lagged(_)) => {}
                Err(broadcast::error::RecvError::Closed) => break,
            },
            _ = ping.tick() => {
                // A peer that vanished without closing (no FIN, no reset) is dropped.
                if s.heard.elapsed() > SILENCE_LIMIT || s.socket.send(Message::Ping(Default::default())).await.is_err() {
                    break;
                }
            }
        }
    }
    let mut socket = s.socket;
    // Frames end when the scene is deleted: its Deleted event is already waiting.
    while let Ok(e) = events.try_recv() {
        if socket.send(event_message(&e)).await.is_err() {
            break;
        }
    }
    let close = close.unwrap_or(CloseFrame { code: close_code::NORMAL, reason: "".into() });
    let _ = socket.send(Message::Close(Some(close))).await;
}
