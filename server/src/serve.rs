//! `floe serve`: the simulation server, gRPC and HTTP. Listeners are bound by
//! the caller (so tests can bind port 0), shutdown is a future (SIGINT/SIGTERM
//! in the binary, a channel in tests), and every scene worker is stopped before
//! `run` returns.

use crate::grpc::Grpc;
use crate::service::{Registry, SceneSource};
use floe_proto::pb::scene_service_server::SceneServiceServer;
use std::future::{Future, IntoFuture};
use std::path::PathBuf;
use std::sync::Arc;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio_stream::wrappers::TcpListenerStream;

/// Largest gRPC request accepted (bytes): room for large scene documents, far
/// below what could hurt the server. Bigger requests get OUT_OF_RANGE.
pub const MAX_REQUEST_BYTES: usize = 8 << 20;

/// The server's listeners, bound by the caller.
#[derive(Debug)]
pub struct Listeners {
    /// gRPC.
    pub grpc: TcpListener,
    /// HTTP: viewer, REST, WebSocket.
    pub http: TcpListener,
}

/// Serves gRPC and HTTP until `shutdown` resolves. Then every scene is deleted
/// first, which ends its frame and event streams and WebSockets, so the
/// graceful shutdown of both transports does not wait on streams that would
/// never end.
pub async fn run(
    listeners: Listeners,
    registry: Arc<Registry>,
    web_root: PathBuf,
    shutdown: impl Future<Output = ()>,
) -> anyhow::Result<()> {
    let (health_reporter, health) = tonic_health::server::health_reporter();
    health_reporter.set_serving::<SceneServiceServer<Grpc>>().await;
    let reflection = tonic_reflection::server::Builder::configure()
        .register_encoded_file_descriptor_set(floe_proto::pb::FILE_DESCRIPTOR_SET)
        .build_v1()?;
    let scenes = SceneServiceServer::new(Grpc::new(registry.clone())).max_decoding_message_size(MAX_REQUEST_BYTES);
    let (stop_tx, stop_rx) = watch::channel(false);
    let stopped = |mut rx: watch::Receiver<bool>| async move {
        let _ = rx.wait_for(|s| *s).await;
    };
    let app = crate::http::router(registry.clone(), web_root);
    let stopper = async move {
        shutdown.await;
        let _ = tokio::task::spawn_blocking(move || registry.shutdown()).await;
        let _ = stop_tx.send(true);
    };
    let grpc = tonic::transport::Server::builder()
        .add_service(health)
        .add_service(reflection)
        .add_service(scenes)
        .serve_with_incoming_shutdown(TcpListenerStream::new(listeners.grpc), stopped(stop_rx.clone()));
    let http = axum::serve(listeners.http, app).with_graceful_shutdown(stopped(stop_rx)).into_future();
    let ((), grpc, http) = tokio::join!(stopper, grpc, http);
    grpc?;
    http?;
    Ok(())
}

/// Resolves on SIGINT (Ctrl-C) or SIGTERM.
pub async fn signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {},
        _ = term => {},
    }
    tracing::info!("shutting down");
}

/// `floe serve` from the command line.
pub fn serve(args: crate::cli::ServeArgs) -> anyhow::Result<()> {
    let runtime = tokio::runtime::Runtime::new()?;
    runtime.block_on(async {
        let grpc = TcpListener::bind(&args.grpc)
            .await
            .map_err(|e| anyhow::anyhow!("cannot listen for gRPC on {}: {e}", args.grpc))?;
        let http = TcpListener::bind(&args.http)
            .await
            .map_err(|e| anyhow::anyhow!("cannot listen for HTTP on {}: {e}", args.http))?;
        let web_root = args.web.clone().unwrap_or_else(default_web_root);
        if !web_root.join("index.html").exists() {
            tracing::warn!("no viewer at {} (pass --web DIR); the API still works", web_root.display());
        }
        let backend = tokio::task::spawn_blocking(move || floe_gpu::select::select(args.backend.into())).await??;
        let registry = Arc::new(Registry::new(args.limits(), backend.factory));
        if args.scene != "none" {
            let r = registry.clone();
            let preset = args.scene.clone();
            let handle = tokio::task::spawn_blocking(move || r.create(SceneSource::Preset(preset), &[])).await??;
            tracing::info!("default scene '{}' is scene {}", args.scene, handle.shared.id);
        }
        tracing::info!("gRPC (floe.v1.SceneService, health, reflection) on {}", grpc.local_addr()?);
        tracing::info!("REST and WebSocket API on http://{}/api/v1", http.local_addr()?);
        println!("Floe viewer: http://{}/", http.local_addr()?);
        run(Listeners { grpc, http }, registry, web_root, signal()).await
    })
}

/// The viewer's files: `web/` of this source tree when it is there (a `cargo run`
/// from a checkout), else `web/` in the working directory.
fn default_web_root() -> PathBuf {
    let source = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../web");
    if source.join("index.html").exists() { source } else { PathBuf::from("web") }
}
