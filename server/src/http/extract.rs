//! Extractors whose rejections are [`ApiError`]s: a malformed body, a scene id that is not a
//! number or a bad query parameter gets the same `{"error": "..."}` JSON, naming what was
//! wrong, as every other error of the API, instead of axum's plain-text rejections.

use super::ApiError;
use axum::extract::{FromRequest, FromRequestParts, OptionalFromRequest, Path, Query, Request};
use axum::http::StatusCode;
use axum::http::request::Parts;
use axum::{Json, extract::rejection::JsonRejection};
use serde::de::DeserializeOwned;

/// A JSON request body.
#[derive(Debug)]
pub struct Body<T>(pub T);

/// 413 (too large) and 415 (not JSON) keep their status; a body that is not valid JSON, or
/// not the expected fields, is a 400 like every other bad request (axum says 422 for the
/// latter).
fn body_error(e: JsonRejection) -> ApiError {
    let status = match e.status() {
        StatusCode::UNPROCESSABLE_ENTITY => StatusCode::BAD_REQUEST,
        other => other,
    };
    ApiError::new(status, e.body_text())
}

impl<S: Send + Sync, T: DeserializeOwned> FromRequest<S> for Body<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let Json(value) = <Json<T> as FromRequest<S>>::from_request(req, state).await.map_err(body_error)?;
        Ok(Body(value))
    }
}

/// An optional body: none when the request has no content type.
impl<S: Send + Sync, T: DeserializeOwned> OptionalFromRequest<S> for Body<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Option<Self>, ApiError> {
        let value = <Json<T> as OptionalFromRequest<S>>::from_request(req, state).await.map_err(body_error)?;
        Ok(value.map(|Json(v)| Body(v)))
    }
}

/// The `{id}` of a scene's path.
#[derive(Debug, Clone, Copy)]
pub struct SceneId(pub u64);

impl<S: Send + Sync> FromRequestParts<S> for SceneId {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Path(id) = Path::<u64>::from_request_parts(parts, state).await.map_err(|e| {
            ApiError::new(StatusCode::BAD_REQUEST, format!("scene id: {}", crate::echo::cap(&e.body_text())))
        })?;
        Ok(SceneId(id))
    }
}

/// Query parameters.
#[derive(Debug)]
pub struct Params<T>(pub T);

impl<S: Send + Sync, T: DeserializeOwned> FromRequestParts<S> for Params<T> {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Query(value) =
            Query::from_request_parts(parts, state).await.map_err(|e| ApiError::new(e.status(), e.body_text()))?;
        Ok(Params(value))
    }
}

/// The caller [`super::guard::guard`] authenticated; a request that did not pass the
/// guard is refused rather than trusted.
#[derive(Debug, Clone)]
pub struct Who(pub crate::auth::Caller);

impl<S: Send + Sync> FromRequestParts<S> for Who {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _: &S) -> Result<Self, ApiError> {
        let caller = parts.extensions.get::<crate::auth::Caller>().cloned();
        caller.map(Who).ok_or_else(|| ApiError::new(StatusCode::UNAUTHORIZED, "the call was not authenticated".into()))
    }
}
