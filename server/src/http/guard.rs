//! What every HTTP request passes through.
//!
//! - [`guard`] (the API and `/metrics`): authentication (`authorization: Bearer
//!   <token>`, or for a WebSocket a token offered as a protocol), the caller's
//!   request rate, and one count and one latency per request in the metrics, by route
//!   and status.
//! - [`bounded_head_and_json_errors`] (everything): a URI or header block over Floe's
//!   limits gets 414 or 431 with the API's JSON error, and an error answer without a
//!   body (405 from the router or the file server) gets one. Requests beyond the
//!   HTTP library's own, larger limits (64 KiB of URI, about 400 KiB of head, 100
//!   headers) are refused by it before Floe sees them, with an empty body.

use super::ApiError;
use crate::auth;
use crate::service::Registry;
use axum::extract::{MatchedPath, Request, State};
use axum::http::{StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use std::sync::Arc;
use std::time::Instant;

/// Longest request URI (bytes).
pub const MAX_URI_BYTES: usize = 8 << 10;
/// Largest header block (names and values, bytes).
pub const MAX_HEADER_BYTES: usize = 32 << 10;

/// Authenticates an API request, takes it from the caller's request rate, and
/// records it in the metrics.
pub async fn guard(State(registry): State<Arc<Registry>>, mut request: Request, next: Next) -> Response {
    let t0 = Instant::now();
    let route = request.extensions().get::<MatchedPath>().map_or("unmatched", MatchedPath::as_str);
    let label = format!("{} {route}", request.method());
    let response = match auth::authorize(&registry, request.headers()) {
        Ok(caller) => {
            request.extensions_mut().insert(caller);
            next.run(request).await
        }
        Err(e) => ApiError::from(e).into_response(),
    };
    registry.metrics().observe("http", &label, response.status().as_str(), t0.elapsed().as_secs_f64());
    response
}

/// Refuses a request head over Floe's limits with 414 or 431, and gives error
/// answers without a body the API's JSON error.
pub async fn bounded_head_and_json_errors(request: Request, next: Next) -> Response {
    let uri = request.uri().to_string().len();
    if uri > MAX_URI_BYTES {
        let m = format!("the URI is {uri} bytes; at most {MAX_URI_BYTES} are accepted");
        return ApiError::new(StatusCode::URI_TOO_LONG, m).into_response();
    }
    let head: usize = request.headers().iter().map(|(k, v)| k.as_str().len() + v.len() + 4).sum();
    if head > MAX_HEADER_BYTES {
        let m = format!("the request headers are {head} bytes; at most {MAX_HEADER_BYTES} are accepted");
        return ApiError::new(StatusCode::REQUEST_HEADER_FIELDS_TOO_LARGE, m).into_response();
    }
    let (method, path) = (request.method().clone(), request.uri().path().to_owned());
    let response = next.run(request).await;
    let empty = response.headers().get(header::CONTENT_LENGTH).is_some_and(|l| l == "0")
        || axum::body::HttpBody::size_hint(response.body()).exact() == Some(0);
    if !(response.status().is_client_error() || response.status().is_server_error()) || !empty {
        return response;
    }
    let status = response.status();
    let message = match status {
        // The router adds the Allow header (the methods that are allowed) afterwards.
        StatusCode::METHOD_NOT_ALLOWED => format!("{method} is not allowed on {}", crate::echo::cap(&path)),
        s => s.canonical_reason().unwrap_or("error").to_owned(),
    };
    let mut json = ApiError::new(status, message).into_response();
    if let Some(allow) = response.headers().get(header::ALLOW) {
        json.headers_mut().insert(header::ALLOW, allow.clone());
    }
    json
}
