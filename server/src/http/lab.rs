//! The lab routes of the REST API: checkpoints, share links, the calling user,
//! users and quotas (admins), and `/metrics` (admins).

use super::{ApiError, ApiResult, Body, SceneId, Who};
use crate::quota::{self, Limit};
use crate::service::{Registry, UserView, require_admin};
use axum::extract::{Path, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{delete, get, post, put};
use axum::{Json, Router};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The routes, under `/api/v1`.
pub fn routes() -> Router<Arc<Registry>> {
    Router::new()
        .route("/scenes/{id}/checkpoint", post(checkpoint))
        .route("/scenes/{id}/shares", get(shares).post(share))
        .route("/scenes/{id}/shares/{share}", delete(revoke))
        .route("/me", get(me))
        .route("/users", get(users))
        .route("/users/{name}/quotas/{quota}", put(set_quota).delete(clear_quota))
}

/// A checkpoint written.
#[derive(Debug, Serialize)]
struct CheckpointView {
    scene_id: u64,
    sequence: u64,
    step: u64,
    sim_time: f64,
}

async fn checkpoint(State(r): State<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<CheckpointView> {
    let m = r.checkpoint(&who, id).await?;
    Ok(Json(CheckpointView { scene_id: id, sequence: m.sequence, step: m.step, sim_time: m.time }))
}

/// A scene's share links.
#[derive(Debug, Serialize)]
struct SharesView {
    scene_id: u64,
    share_ids: Vec<String>,
}

/// A new share link: the token is shown once.
#[derive(Debug, Serialize)]
struct ShareView {
    scene_id: u64,
    share_id: String,
    token: String,
    /// The viewer's address for the link, relative to the server.
    viewer: String,
}

async fn shares(State(r): State<Arc<Registry>>, Who(who): Who, SceneId(id): SceneId) -> ApiResult<SharesView> {
    Ok(Json(SharesView { scene_id: id, share_ids: r.shares(&who, id)? }))
}

async fn share(
    State(r): State<Arc<Registry>>,
    Who(who): Who,
    SceneId(id): SceneId,
) -> Result<(StatusCode, Json<ShareView>), ApiError> {
    let (token, share_id) = r.share(&who, id).await?;
    let viewer = format!("/#scene={id}&token={token}");
    Ok((StatusCode::CREATED, Json(ShareView { scene_id: id, share_id, token, viewer })))
}

async fn revoke(
    State(r): State<Arc<Registry>>,
    Who(who): Who,
    Path((id, share)): Path<(String, String)>,
) -> ApiResult<SharesView> {
    let id: u64 = id.parse().map_err(|_| {
        ApiError::new(StatusCode::BAD_REQUEST, format!("scene id: not a number: {}", crate::echo::cap(&id)))
    })?;
    r.revoke_share(&who, id, &share).await?;
    Ok(Json(SharesView { scene_id: id, share_ids: r.shares(&who, id)? }))
}

/// A user as JSON.
#[derive(Debug, Serialize)]
pub struct UserJson {
    name: String,
    admin: bool,
    /// Quota name -> value in force.
    quotas: serde_json::Map<String, serde_json::Value>,
    /// The quotas that are the user's own overrides.
    overridden: Vec<&'static str>,
    scenes: u64,
    running_scenes: u64,
    running_particles: u64,
    open_streams: u64,
}

impl From<UserView> for UserJson {
    fn from(u: UserView) -> Self {
        Self {
            quotas: Limit::ALL.iter().map(|&l| (l.name().to_owned(), u.quotas.get(l).into())).collect(),
            overridden: u.overridden.iter().map(|l| l.name()).collect(),
            name: u.name,
            admin: u.admin,
            scenes: u.scenes,
            running_scenes: u.running_scenes,
            running_particles: u.running_particles,
            open_streams: u.open_streams,
        }
    }
}

async fn me(State(r): State<Arc<Registry>>, Who(who): Who) -> ApiResult<UserJson> {
    Ok(Json(r.whoami(&who)?.into()))
}

async fn users(State(r): State<Arc<Registry>>, Who(who): Who) -> ApiResult<Vec<UserJson>> {
    Ok(Json(r.users(&who)?.into_iter().map(UserJson::from).collect()))
}

/// `PUT /users/{name}/quotas/{quota}` body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuotaBody {
    value: u64,
}

fn limit(name: &str) -> Result<Limit, ApiError> {
    quota::limit_named(name).map_err(|m| ApiError::new(StatusCode::BAD_REQUEST, m))
}

async fn set_quota(
    State(r): State<Arc<Registry>>,
    Who(who): Who,
    Path((name, quota)): Path<(String, String)>,
    Body(b): Body<QuotaBody>,
) -> ApiResult<UserJson> {
    require_admin(&who)?;
    let l = limit(&quota)?;
    let value =
        quota::check_value(l, b.value).map_err(|m| ApiError::new(StatusCode::BAD_REQUEST, format!("value: {m}")))?;
    Ok(Json(r.set_quota(&who, &name, l, Some(value)).await?.into()))
}

async fn clear_quota(
    State(r): State<Arc<Registry>>,
    Who(who): Who,
    Path((name, quota)): Path<(String, String)>,
) -> ApiResult<UserJson> {
    require_admin(&who)?;
    let l = limit(&quota)?;
    Ok(Json(r.set_quota(&who, &name, l, None).await?.into()))
}

/// `GET /metrics`: Prometheus text format, for admins.
pub async fn metrics(State(r): State<Arc<Registry>>, Who(who): Who) -> Result<Response, ApiError> {
    require_admin(&who)?;
    let text = r.metrics().render();
    Ok(([(header::CONTENT_TYPE, "text/plain; version=0.0.4; charset=utf-8")], text).into_response())
}
