//! The HTTP adapter: the viewer's static files at `/`, a REST + JSON mirror of
//! the control calls under `/api/v1`, and a WebSocket per scene ([`crate::ws`]).
//!
//! | method | path | does |
//! |---|---|---|
//! | GET | `/api/v1/presets` | preset names |
//! | GET, POST | `/api/v1/scenes` | list; create (`{"preset": "dam_break", "overrides": [...]}` or `{"document": "...", "document_format": "toml"}`; optional `"backend": "gpu"` or `"cpu"`) |
//! | GET, DELETE | `/api/v1/scenes/{id}` | get; delete |
//! | POST | `/api/v1/scenes/{id}/step` | `{"steps": 10}` or `{"until_time": 0.5}` |
//! | POST | `/api/v1/scenes/{id}/reset` | back to t = 0 with the current settings |
//! | POST | `/api/v1/scenes/{id}/run`, `/pause` | `{"real_time_factor": 1.0}` (0 = as fast as possible) |
//! | GET | `/api/v1/scenes/{id}/stats` | throughput and streaming statistics |
//! | GET | `/api/v1/scenes/{id}/terrain` | each terrain's height grid: `{"terrains": [{"boundary", "min", "max", "nx", "nz", "heights"}]}` |
//! | POST | `/api/v1/scenes/{id}/parameters` | `{"overrides": ["gravity=[0,-1,0]"]}`: change tunable settings |
//! | GET, PUT | `/api/v1/scenes/{id}/snapshot` | the full state as bytes; restore a paused scene from them |
//! | GET | `/api/v1/scenes/{id}/ws` | WebSocket: binary frames, JSON control and events |
//! | POST | `/api/v1/scenes/{id}/checkpoint` | write a checkpoint now |
//! | GET, POST | `/api/v1/scenes/{id}/shares` | share link ids; create a read-only share link (its token, once) |
//! | DELETE | `/api/v1/scenes/{id}/shares/{share_id}` | revoke a share link |
//! | GET | `/api/v1/me` | the calling user: quotas and usage |
//! | GET | `/api/v1/users` | admin: every user with quotas and usage |
//! | PUT, DELETE | `/api/v1/users/{name}/quotas/{quota}` | admin: `{"value": 4}` sets a user's quota; DELETE clears it |
//! | GET | `/metrics` | admin: Prometheus metrics |
//!
//! Calls need `authorization: Bearer <token>` on a server with users ([`guard`]).
//! Errors are `{"error": "..."}` with 400 (bad request, naming the field), 401 (no or a
//! bad token), 403 (admin only; steering through a share link), 404 (unknown scene, or
//! another user's), 405 (method), 409 (wrong state), 413 (body too large), 414 (URI too
//! long), 415 (a body that is not `application/json`), 429 (server full, a quota reached)
//! or 431 (headers too large); malformed bodies, ids and query parameters included
//! ([`extract`]).

use crate::auth::Caller;
use crate::service::{MAX_STEPS_PER_REQUEST, Need};
use crate::service::{Placing, Registry, SceneSource};
use axum::extract::{DefaultBodyLimit, State as AxState};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router, middleware};
use floe_engine::scene::load::Format;
use serde::Deserialize;
use std::sync::Arc;

mod error;
mod extract;
pub mod guard;
mod lab;
mod terrain;
mod view;

pub use error::ApiError;
pub use view::{ChannelView, MaterialView, MeasureView, SceneView, SetView, state_name};

pub use extract::{Body, Params, SceneId, Who};

/// Largest request body (bytes), as for gRPC.
pub const MAX_BODY_BYTES: usize = crate::serve::MAX_REQUEST_BYTES;

/// The router: API, metrics, and the viewer's files from `web_root`.
pub fn router(registry: Arc<Registry>, web_root: std::path::PathBuf) -> Router {
    let api = Router::new()
        .route("/presets", get(presets))
        .route("/scenes", get(list).post(create))
        .route("/scenes/{id}", get(scene).delete(delete))
        .route("/scenes/{id}/step", post(step))
        .route("/scenes/{id}/run", post(run))
        .route("/scenes/{id}/pause", post(pause))
        .route("/scenes/{id}/reset", post(reset))
        .route("/scenes/{id}/stats", get(stats))
        .route("/scenes/{id}/terrain", get(terrain::terrain))
        .route("/scenes/{id}/snapshot", get(snapshot).put(restore))
        .route("/scenes/{id}/parameters", post(parameters))
        .route("/scenes/{id}/ws", get(crate::ws::upgrade))
        .merge(lab::routes())
        .fallback(|| async { ApiError::new(StatusCode::NOT_FOUND, "no such API route".into()) })
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES));
    let guarded = Router::new()
        .nest("/api/v1", api)
        .route("/metrics", get(lab::metrics))
        .route_layer(middleware::from_fn_with_state(registry.clone(), guard::guard))
        .with_state(registry);
    guarded
        .fallback_service(tower_http::services::ServeDir::new(web_root))
        .layer(middleware::from_fn(guard::bounded_head_and_json_errors))
}

type ApiResult<T> = Result<Json<T>, ApiError>;

async fn presets() -> Json<Vec<&'static str>> {
    Json(floe_engine::scene::presets::names())
}

async fn list(AxState(r): AxState<Arc<Registry>>, Who(who): Who) -> Json<Vec<SceneView>> {
    let here = r.worker_name();
    let mut views: Vec<SceneView> = r.list(&who).iter().map(|h| SceneView::of(&h.shared, here)).collect();
    views.extend(r.placed_elsewhere(&who).into_iter().map(|p| SceneView {
        scene_id: p.id,
        worker: p.worker,
        name: p.name,
        owner: p.owner,
        state: match p.state.as_str() {
            "running" => "running",
            "halted" => "halted",
            _ => "paused",
        },
        particles: usize::try_from(p.particles).unwrap_or(usize::MAX),
        ..SceneView::default()
    }));
    views.sort_by_key(|v| v.scene_id);
    Json(views)
}

/// `POST /scenes` body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CreateBody {
    preset: Option<String>,
    document: Option<String>,
    #[serde(default)]
    document_format: Option<String>,
    #[serde(default)]
    overrides: Vec<String>,
    /// `gpu`, `cpu`, or none (any).
    #[serde(default)]
    backend: Option<String>,
}

async fn create(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    headers: axum::http::HeaderMap,
    Body(b): Body<CreateBody>,
) -> Result<(StatusCode, Json<SceneView>), ApiError> {
    let named = headers.get(crate::cluster::WORKER_HEADER).and_then(|v| v.to_str().ok());
    let source = match (b.preset, b.document) {
        (Some(p), None) => SceneSource::Preset(p),
        (None, Some(text)) => {
            let format = match b.document_format.as_deref() {
                None | Some("toml") => Format::Toml,
                Some("json") => Format::Json,
                Some(other) => {
                    return Err(ApiError::new(
                        StatusCode::BAD_REQUEST,
                        format!("document_format: must be \"toml\" or \"json\", got {:?}", crate::echo::cap(other)),
                    ));
                }
            };
            SceneSource::Document { text, format }
        }
        _ => {
            return Err(ApiError::new(
                StatusCode::BAD_REQUEST,
                "give exactly one of \"preset\" and \"document\"".into(),
            ));
        }
    };
    let placing = Placing { worker: named, backend: b.backend.as_deref(), size: None };
    let handle = r.create_routed(&who, source, b.overrides, placing).await?;
    Ok((StatusCode::CREATED, Json(SceneView::of(&handle.shared, r.worker_name()))))
}

/// The view of a scene the caller may watch.
fn view(r: &Registry, who: &Caller, id: u64) -> ApiResult<SceneView> {
    Ok(Json(SceneView::of(&r.get(who, id, Need::Watch)?.shared, r.worker_name())))
}

async fn scene(AxState(r): AxState<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<SceneView> {
    view(&r, &who, id)
}

async fn stats(state: AxState<Arc<Registry>>, who: Who, id: SceneId) -> ApiResult<SceneView> {
    scene(state, who, id).await
}

async fn delete(AxState(r): AxState<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<SceneView> {
    let handle = r.delete(&who, id).await?;
    Ok(Json(SceneView::of(&handle.shared, r.worker_name())))
}

/// `POST /scenes/{id}/step` body.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepBody {
    /// Steps to take.
    #[serde(default)]
    pub steps: u64,
    /// Or: simulated time to reach (s).
    #[serde(default)]
    pub until_time: Option<f64>,
}

impl StepBody {
    /// Checks the body: (steps, until).
    pub fn checked(&self) -> Result<(u64, Option<f64>), String> {
        match self.until_time {
            Some(t) if !(t.is_finite() && t >= 0.0) => Err(format!("until_time: must be a time >= 0 s, got {t}")),
            Some(t) => Ok((0, Some(t))),
            None if self.steps == 0 || self.steps > MAX_STEPS_PER_REQUEST => {
                Err(format!("steps: must be between 1 and {MAX_STEPS_PER_REQUEST}, got {}", self.steps))
            }
            None => Ok((self.steps, None)),
        }
    }
}

async fn step(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
    Body(b): Body<StepBody>,
) -> ApiResult<SceneView> {
    let (steps, until) = b.checked().map_err(|m| ApiError::new(StatusCode::BAD_REQUEST, m))?;
    r.step(&who, id, steps, until).await?;
    Ok(Json(SceneView::of(&r.get(&who, id, Need::Watch)?.shared, r.worker_name())))
}

/// `POST /scenes/{id}/run` body.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunBody {
    /// Simulated seconds per wall second; 0 = as fast as possible.
    #[serde(default)]
    pub real_time_factor: f64,
}

impl RunBody {
    /// Checks the body: the real-time factor.
    pub fn checked(&self) -> Result<f64, String> {
        let rtf = self.real_time_factor;
        if rtf.is_finite() && rtf >= 0.0 { Ok(rtf) } else { Err(format!("real_time_factor: must be >= 0, got {rtf}")) }
    }
}

async fn run(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
    body: Option<Body<RunBody>>,
) -> ApiResult<SceneView> {
    let rtf = body.map(|b| b.0).unwrap_or_default().checked().map_err(|m| ApiError::new(StatusCode::BAD_REQUEST, m))?;
    r.run(&who, id, rtf).await?;
    view(&r, &who, id)
}

async fn pause(AxState(r): AxState<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<SceneView> {
    r.pause(&who, id).await?;
    view(&r, &who, id)
}

async fn snapshot(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
) -> Result<Response, ApiError> {
    let state = r.get(&who, id, Need::Steer)?.save().await?;
    Ok(([(axum::http::header::CONTENT_TYPE, "application/octet-stream")], state).into_response())
}

async fn restore(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
    body: axum::body::Bytes,
) -> ApiResult<SceneView> {
    r.restore(&who, id, body.to_vec()).await?;
    view(&r, &who, id)
}

/// `POST /scenes/{id}/parameters` body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParametersBody {
    /// `key=value` overrides of tunable settings.
    pub overrides: Vec<String>,
}

async fn parameters(
    AxState(r): AxState<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
    Body(b): Body<ParametersBody>,
) -> ApiResult<SceneView> {
    r.set_parameters(&who, id, b.overrides).await?;
    view(&r, &who, id)
}

async fn reset(AxState(r): AxState<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<SceneView> {
    r.reset(&who, id).await?;
    view(&r, &who, id)
}
