//! The WebSocket of a scene (`/api/v1/scenes/{id}/ws?channels=velocity&max_fps=30&bits=16&mode=unordered&decimation=1&set=particles`):
//! binary messages carry encoded frames (latest-frame semantics, as over gRPC);
//! text messages are JSON both ways.
//!
//! Client to server: `{"op": "run", "real_time_factor": 1}`, `{"op": "pause"}`,
//! `{"op": "step", "steps": 1}` (or `"until_time"`), `{"op": "set", "overrides": ["gravity=[0,-1,0]"]}`,
//! `{"op": "reset"}`, `{"op": "status"}`.
//! Server to client: `{"type": "status", "scene": {...}}` after each op,
//! `{"type": "event", "event": "halted", "reason": "...", "step": n, "sim_time": t}`,
//! `{"type": "event", "event": "deleted"}` (then the socket closes), and
//! `{"type": "error", "message": "..."}` for a message it could not use; the
//! connection stays open after an error.

use crate::http::{ApiError, Params, RunBody, SceneId, SceneView, StepBody};
use crate::service::Registry;
use crate::service::frames::EncodedFrame;
use crate::service::options::FrameRequest;
use crate::service::{Event, SceneHandle};
use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::response::Response;
use serde::Deserialize;
use std::sync::Arc;
use tokio::sync::{broadcast, mpsc};

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
}

impl WsQuery {
    /// The frame options the query states (checked against the scene by the service).
    fn request(&self) -> FrameRequest {
        FrameRequest {
            channels: self.channels.split(',').map(str::to_string).collect(),
            max_fps: self.max_fps,
            position_bits: self.bits.map(u32::from),
            mode: self.mode.clone(),
            decimation: self.decimation,
            set: self.set.clone(),
        }
    }
}

/// Upgrades to a WebSocket after checking the scene and the options.
pub async fn upgrade(
    State(registry): State<Arc<Registry>>,
    SceneId(id): SceneId,
    Params(q): Params<WsQuery>,
    ws: WebSocketUpgrade,
) -> Result<Response, ApiError> {
    let handle = registry.get(id)?;
    let subscription = registry.subscribe(id, &q.request())?;
    let (tx, frames) = mpsc::channel(1);
    // Frames are made in a task of their own, so a pending encode is never
    // cancelled by the socket loop below; capacity 1 keeps latest-frame semantics.
    let mut subscription = subscription;
    tokio::spawn(async move {
        while let Some(frame) = subscription.next().await {
            if tx.send(frame).await.is_err() {
                break;
            }
        }
    });
    Ok(ws.max_message_size(64 << 10).on_upgrade(move |socket| session(socket, handle, frames)))
}

fn json(value: serde_json::Value) -> Message {
    Message::Text(value.to_string().into())
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
        Event::Deleted => json(serde_json::json!({ "type": "event", "event": "deleted" })),
    }
}

/// A control message from the client.
#[derive(Debug, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case", deny_unknown_fields)]
enum Control {
    Run {
        #[serde(default)]
        real_time_factor: f64,
    },
    Pause,
    Step {
        #[serde(default)]
        steps: u64,
        #[serde(default)]
        until_time: Option<f64>,
    },
    Set {
        overrides: Vec<String>,
    },
    Reset,
    Status,
}

async fn control(handle: &SceneHandle, text: &str) -> Message {
    let op: Control = match serde_json::from_str(text) {
        Ok(op) => op,
        Err(e) => return json(serde_json::json!({ "type": "error", "message": format!("bad control message: {e}") })),
    };
    let result = match op {
        Control::Run { real_time_factor } => {
            let b = RunBody { real_time_factor };
            if !(b.real_time_factor.is_finite() && b.real_time_factor >= 0.0) {
                Err(format!("real_time_factor: must be >= 0, got {}", b.real_time_factor))
            } else {
                handle.run(b.real_time_factor).await.map(|_| ()).map_err(|e| e.to_string())
            }
        }
        Control::Pause => handle.pause().await.map(|_| ()).map_err(|e| e.to_string()),
        Control::Step { steps, until_time } => match (StepBody { steps, until_time }).checked() {
            Ok((n, until)) => handle.step(n, until).await.map(|_| ()).map_err(|e| e.to_string()),
            Err(m) => Err(m),
        },
        Control::Set { overrides } => handle.set_parameters(overrides).await.map(|_| ()).map_err(|e| e.to_string()),
        Control::Reset => handle.reset().await.map(|_| ()).map_err(|e| e.to_string()),
        Control::Status => Ok(()),
    };
    match result {
        Ok(()) => json(serde_json::json!({ "type": "status", "scene": SceneView::of(&handle.shared) })),
        Err(m) => json(serde_json::json!({ "type": "error", "message": m })),
    }
}

async fn session(
    mut socket: WebSocket,
    handle: Arc<SceneHandle>,
    mut frames: mpsc::Receiver<Result<EncodedFrame, floe_proto::EncodeError>>,
) {
    let mut events = handle.shared.events.subscribe();
    let hello = json(serde_json::json!({ "type": "status", "scene": SceneView::of(&handle.shared) }));
    if socket.send(hello).await.is_err() {
        return;
    }
    loop {
        tokio::select! {
            frame = frames.recv() => match frame {
                Some(Ok(f)) => {
                    if socket.send(Message::Binary(f.data.as_ref().clone().into())).await.is_err() {
                        break;
                    }
                }
                Some(Err(e)) => {
                    let _ = socket.send(json(serde_json::json!({ "type": "error", "message": e.to_string() }))).await;
                }
                None => {
                    // Frames end when the scene is deleted, after its Deleted event was sent:
                    // pass on what is queued so the client hears why the socket closes.
                    while let Ok(e) = events.try_recv() {
                        let _ = socket.send(event_message(&e)).await;
                    }
                    break;
                }
            },
            msg = socket.recv() => match msg {
                Some(Ok(Message::Text(t))) => {
                    let reply = control(&handle, t.as_str()).await;
                    if socket.send(reply).await.is_err() {
                        break;
                    }
                }
                Some(Ok(Message::Binary(_))) => {
                    let m = json(serde_json::json!({ "type": "error", "message": "binary messages are not accepted; send JSON text" }));
                    if socket.send(m).await.is_err() {
                        break;
                    }
                }
                Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                Some(Ok(_)) => {}
            },
            event = events.recv() => match event {
                Ok(e) => {
                    let last = e == Event::Deleted;
                    if socket.send(event_message(&e)).await.is_err() || last {
                        break;
                    }
                }
                Err(broadcast::error::RecvError::Lagged(_)) => {}
                Err(broadcast::error::RecvError::Closed) => break,
            },
        }
    }
    let _ = socket.send(Message::Close(None)).await;
}
