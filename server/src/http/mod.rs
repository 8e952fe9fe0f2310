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
use crate::service::{MAX_STEPS_PER_REQUEST, Need, Shared, State};
use crate::service::{Placing, Registry, SceneSource, ServiceError};
use axum::extract::{DefaultBodyLimit, State as AxState};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router, middleware};
use floe_engine::scene::load::Format;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::sync::atomic::Ordering;

mod extract;
pub mod guard;
mod lab;
mod terrain;

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

/// An error response: a status and a message naming what was wrong.
#[derive(Debug)]
pub struct ApiError {
    /// The HTTP status.
    pub status: StatusCode,
    /// What was wrong, naming the field.
    pub message: String,
    /// In a cluster, the worker the request is for (421 Misdirected Request): the
    /// answer's `floe-worker` header and `worker` field, and the client retries at
    /// `/w/WORKER/...` through the proxy.
    pub worker: Option<String>,
}

impl ApiError {
    /// An error with this status and message.
    pub fn new(status: StatusCode, message: String) -> Self {
        Self { status, message, worker: None }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = Json(serde_json::json!({ "error": crate::echo::bounded(&self.message), "worker": self.worker }));
        if self.status == StatusCode::UNAUTHORIZED {
            return (self.status, [(axum::http::header::WWW_AUTHENTICATE, "Bearer")], body).into_response();
        }
        if let Some(worker) = &self.worker {
            return (self.status, [(crate::cluster::WORKER_HEADER, worker.as_str())], body).into_response();
        }
        (self.status, body).into_response()
    }
}

impl From<ServiceError> for ApiError {
    fn from(e: ServiceError) -> Self {
        let code = match e {
            ServiceError::NotFound(_) | ServiceError::Missing(_) => StatusCode::NOT_FOUND,
            ServiceError::InvalidArgument(_) => StatusCode::BAD_REQUEST,
            ServiceError::FailedPrecondition(_) => StatusCode::CONFLICT,
            ServiceError::ResourceExhausted(_) => StatusCode::TOO_MANY_REQUESTS,
            ServiceError::PermissionDenied(_) => StatusCode::FORBIDDEN,
            ServiceError::Unavailable(_) => StatusCode::SERVICE_UNAVAILABLE,
            ServiceError::Unauthenticated(_) => StatusCode::UNAUTHORIZED,
            ServiceError::Elsewhere { ref worker, .. } => {
                return ApiError {
                    status: StatusCode::MISDIRECTED_REQUEST,
                    worker: Some(worker.clone()),
                    message: e.to_string(),
                };
            }
        };
        ApiError::new(code, e.to_string())
    }
}

impl From<crate::service::CommandError> for ApiError {
    fn from(e: crate::service::CommandError) -> Self {
        ServiceError::from(e).into()
    }
}

type ApiResult<T> = Result<Json<T>, ApiError>;

/// A scene as JSON.
#[derive(Debug, Default, Serialize)]
pub struct SceneView {
    /// Scene id.
    pub scene_id: u64,
    /// In a cluster's scene list, the worker holding it: calls for it go to
    /// `/w/WORKER/api/v1/...` through the proxy. Absent on a single server. A list
    /// from one worker gives the others' scenes with their id, name, owner, state,
    /// particles and worker only.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub worker: String,
    /// Name.
    pub name: String,
    /// The user who created it.
    pub owner: String,
    /// `paused`, `running`, `halted` or `deleted`.
    pub state: &'static str,
    /// Simulated time (s).
    pub sim_time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Fluid particles.
    pub particles: usize,
    /// Particle spacing (m), for drawing particles at their size.
    pub particle_spacing: f32,
    /// The backend stepping the scene: `gpu` or `cpu`.
    pub backend: &'static str,
    /// Domain (m).
    pub bounds_min: [f32; 3],
    /// Domain (m).
    pub bounds_max: [f32; 3],
    /// Why it halted, if it did.
    pub halt_reason: Option<String>,
    /// Steps per wall second.
    pub steps_per_second: f64,
    /// The last dt (s).
    pub dt: f64,
    /// Open frame streams.
    pub subscribers: u32,
    /// Frames skipped by slow subscribers.
    pub dropped_frames: u64,
    /// The resolved scene, live changes included.
    pub scene: serde_json::Value,
    /// Snapshots published.
    pub frames_published: u64,
    /// The channels the scene offers for frames, with wire tags and units.
    pub channels: Vec<ChannelView>,
    /// The scene's particle sets, with counts and the index frames carry.
    pub sets: Vec<SetView>,
    /// The scene's materials, in the order of the `material` channel's indices.
    pub materials: Vec<MaterialView>,
    /// The settings `parameters` may change.
    pub tunables: Vec<floe_engine::scene::tunable::Tunable>,
    /// What the scheme and modules measured (refreshed at most twice a second while
    /// running, and whenever stepping stops), by name.
    pub measures: std::collections::BTreeMap<String, MeasureView>,
}

/// A channel a scene offers.
#[derive(Debug, Serialize)]
pub struct ChannelView {
    /// Name to ask for.
    pub name: &'static str,
    /// Wire tag.
    pub tag: u8,
    /// SI unit.
    pub unit: &'static str,
    /// Values per particle.
    pub components: u8,
    /// Particle set.
    pub set: &'static str,
    /// Sent exactly (raw u8).
    pub exact: bool,
    /// What it holds.
    pub about: &'static str,
    /// Declaring module.
    pub module: &'static str,
}

/// A particle set of a scene.
#[derive(Debug, Serialize)]
pub struct SetView {
    /// Name.
    pub name: &'static str,
    /// Particles (or cells) in it.
    pub count: usize,
    /// Its frames' set byte.
    pub index: usize,
    /// Whether it is a grid (its frames are grid frames, cells x fastest).
    pub grid: bool,
    /// How viewers draw it (`snow`, ...; absent: as a module's points or a field's colours).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub look: Option<&'static str>,
    /// For a grid: the channel of its cells' surface heights (m), where viewers draw them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface: Option<&'static str>,
    /// For a grid in a look: the channel (0 to 1) scaling how much of the look viewers draw.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shade: Option<&'static str>,
}

/// A material of a scene.
#[derive(Debug, Serialize)]
pub struct MaterialView {
    /// Name, as the scene file gives it.
    pub name: String,
    /// `fluid` or `solid`.
    pub kind: &'static str,
    /// Rest density (kg/m^3).
    pub rest_density: f32,
    /// How viewers draw it: `water`, `snow`, `ice` or `solid`.
    pub look: &'static str,
}

/// A value a scene reports.
#[derive(Debug, Serialize)]
pub struct MeasureView {
    /// The value.
    pub value: f64,
    /// Its SI unit.
    pub unit: String,
}

/// Name of a state in JSON.
pub fn state_name(s: State) -> &'static str {
    match s {
        State::Paused => "paused",
        State::Running => "running",
        State::Halted => "halted",
        State::Deleted => "deleted",
    }
}

impl SceneView {
    /// The view now of a scene held by `worker` (empty on a single server).
    pub fn of(shared: &Shared, worker: &str) -> Self {
        let s = shared.status();
        Self {
            scene_id: shared.id,
            worker: worker.to_owned(),
            name: shared.name.clone(),
            owner: shared.owner.clone(),
            state: state_name(s.state),
            sim_time: s.time,
            steps: s.steps,
            particles: shared.particles,
            particle_spacing: shared.particle_spacing,
            backend: shared.backend,
            bounds_min: shared.bounds.0,
            bounds_max: shared.bounds.1,
            halt_reason: s.halt_reason,
            steps_per_second: s.steps_per_second,
            dt: s.dt,
            subscribers: shared.subscribers.load(Ordering::Relaxed),
            dropped_frames: shared.dropped_frames(),
            frames_published: shared.published.load(Ordering::Relaxed),
            scene: serde_json::from_str(&shared.scene_json()).unwrap_or_default(),
            channels: shared
                .channels
                .iter()
                .map(|c| ChannelView {
                    name: c.spec.name,
                    tag: c.kind.tag(),
                    unit: c.spec.unit,
                    components: c.spec.components,
                    set: c.spec.set,
                    exact: c.spec.exact,
                    about: c.spec.about,
                    module: c.spec.module,
                })
                .collect(),
            sets: shared
                .sets
                .iter()
                .enumerate()
                .map(|(index, s)| SetView {
                    name: s.name,
                    count: s.count,
                    index,
                    grid: s.grid,
                    look: s.look,
                    surface: s.surface,
                    shade: s.shade,
                })
                .collect(),
            materials: shared
                .materials
                .iter()
                .map(|m| MaterialView {
                    name: m.name.clone(),
                    kind: m.kind.name(),
                    rest_density: m.rest_density,
                    look: m.look.name(),
                })
                .collect(),
            tunables: shared.tunables.clone(),
            measures: s
                .measures
                .iter()
                .map(|m| (m.name.clone(), MeasureView { value: m.value, unit: m.unit.clone() }))
                .collect(),
        }
    }
}

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
    let placing = Placing { worker: named, backend: b.backend.as_deref() };
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
