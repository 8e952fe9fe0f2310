//! What every gRPC call passes through before and after its handler (a tower layer
//! on the gRPC server):
//!
//! - authentication (`authorization: Bearer <token>`) and the caller's request rate;
//!   the caller goes into the request's extensions for the handlers. Health checks
//!   and reflection need no token, so load balancers and tools like grpcurl work.
//! - metrics: one count and one latency per call, by method and code.
//! - a request the server cannot decode (invalid UTF-8 in a string, an invalid field
//!   key) is the client's error: tonic answers INTERNAL, this answers INVALID_ARGUMENT.

use crate::auth;
use crate::convert::status;
use crate::service::Registry;
use std::future::Future;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::Instant;
use tonic::codegen::http;
use tonic::{Code, Status};

/// Prefix of the paths that need a caller (Floe's own services).
const GUARDED: &str = "/floe.v1.";
/// How tonic's prost codec words a request it could not decode.
const DECODE_FAILURE: &str = "failed to decode Protobuf message";

/// The layer, over one registry.
#[derive(Debug, Clone)]
pub struct GuardLayer(pub Arc<Registry>);

impl<S> tower::Layer<S> for GuardLayer {
    type Service = Guard<S>;

    fn layer(&self, inner: S) -> Guard<S> {
        Guard { inner, registry: self.0.clone() }
    }
}

/// The service the layer wraps around the gRPC routes.
#[derive(Debug, Clone)]
pub struct Guard<S> {
    inner: S,
    registry: Arc<Registry>,
}

/// The gRPC code name of a response, from its `grpc-status` header (a trailers-only
/// answer: an error); "OK" when the status follows the body in trailers.
fn code_of(headers: &http::HeaderMap) -> Code {
    Status::from_header_map(headers).map_or(Code::Ok, |s| s.code())
}

/// Rewrites tonic's INTERNAL for an undecodable request to INVALID_ARGUMENT.
fn decode_failure_is_the_clients(headers: &mut http::HeaderMap) {
    let Some(s) = Status::from_header_map(headers) else { return };
    if s.code() == Code::Internal && s.message().starts_with(DECODE_FAILURE) {
        let fixed = Status::invalid_argument(crate::echo::bounded(&format!(
            "the request could not be decoded: {}",
            s.message()
        )));
        headers.remove("grpc-message");
        let _ = fixed.add_header(headers);
    }
}

impl<S, B> tower::Service<http::Request<B>> for Guard<S>
where
    S: tower::Service<http::Request<B>, Response = http::Response<tonic::body::Body>> + Clone + Send + 'static,
    S::Future: Send + 'static,
    B: Send + 'static,
{
    type Response = http::Response<tonic::body::Body>;
    type Error = S::Error;
    type Future = Pin<Box<dyn Future<Output = Result<Self::Response, Self::Error>> + Send>>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), Self::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, mut request: http::Request<B>) -> Self::Future {
        let t0 = Instant::now();
        let path = request.uri().path();
        let method = path.strip_prefix(GUARDED).unwrap_or(path.trim_start_matches('/')).to_owned();
        let registry = self.registry.clone();
        if path.starts_with(GUARDED) {
            match auth::authorize(&registry, request.headers()) {
                Ok(caller) => {
                    request.extensions_mut().insert(caller);
                }
                Err(e) => {
                    let refusal = status(e);
                    registry.metrics().observe(
                        "grpc",
                        &method,
                        &format!("{:?}", refusal.code()),
                        t0.elapsed().as_secs_f64(),
                    );
                    return Box::pin(async move { Ok(refusal.into_http()) });
                }
            }
        }
        // The clone that was made ready serves this call; the fresh one waits for the next.
        let clone = self.inner.clone();
        let mut inner = std::mem::replace(&mut self.inner, clone);
        Box::pin(async move {
            let mut response = inner.call(request).await?;
            decode_failure_is_the_clients(response.headers_mut());
            let code = code_of(response.headers());
            registry.metrics().observe("grpc", &method, &format!("{code:?}"), t0.elapsed().as_secs_f64());
            Ok(response)
        })
    }
}
