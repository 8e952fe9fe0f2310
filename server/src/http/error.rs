//! The REST calls' error answer: a status, a message naming what was wrong, and in a
//! cluster the worker a misdirected call is for.

use crate::service::ServiceError;
use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};

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
