//! `floe serve`: the simulation server, gRPC and HTTP. Listeners are bound by
//! the caller (so tests can bind port 0), shutdown is a future (SIGINT/SIGTERM
//! in the binary, a channel in tests), and every scene is checkpointed and its
//! worker stopped before `run` returns.

use crate::auth::{AuthMode, Caller};
use crate::cli::AuthChoice;
use crate::cluster::Member;
use crate::grpc::Grpc;
use crate::grpc_guard::GuardLayer;
use crate::grpc_lab::Lab;
use crate::service::{PresetSize, Registry, SceneSource};
use crate::store::Store;
use crate::store::cluster::WorkerInfo;
use axum::serve::ListenerExt;
use floe_proto::pb::lab_service_server::LabServiceServer;
use floe_proto::pb::scene_service_server::SceneServiceServer;
use std::future::{Future, IntoFuture};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use tokio::net::TcpListener;
use tokio::sync::watch;

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

/// Resolves once `rx` says stop.
async fn stopped(mut rx: watch::Receiver<bool>) {
    let _ = rx.wait_for(|s| *s).await;
}

/// Serves gRPC and HTTP until `shutdown` resolves. Then the periodic work stops,
/// every scene is checkpointed (when the registry keeps a store) and stopped,
/// which ends its frame and event streams and WebSockets, so the graceful shutdown
/// of both transports does not wait on streams that would never end.
pub async fn run(
    listeners: Listeners,
    registry: Arc<Registry>,
    web_root: PathBuf,
    shutdown: impl Future<Output = ()>,
) -> anyhow::Result<()> {
    let (health_reporter, health) = tonic_health::server::health_reporter();
    health_reporter.set_serving::<SceneServiceServer<Grpc>>().await;
    health_reporter.set_serving::<LabServiceServer<Lab>>().await;
    // v1 and v1alpha: grpcio-reflection, older grpcurl and Postman speak v1alpha only.
    let reflection = || {
        tonic_reflection::server::Builder::configure()
            .register_encoded_file_descriptor_set(floe_proto::pb::FILE_DESCRIPTOR_SET)
    };
    let (reflection_v1, reflection_v1alpha) = (reflection().build_v1()?, reflection().build_v1alpha()?);
    let scenes = SceneServiceServer::new(Grpc::new(registry.clone())).max_decoding_message_size(MAX_REQUEST_BYTES);
    let lab = LabServiceServer::new(Lab::new(registry.clone())).max_decoding_message_size(MAX_REQUEST_BYTES);
    let (stop_tx, stop_rx) = watch::channel(false);
    let (maintain_stop, maintain_rx) = watch::channel(false);
    let maintenance = tokio::spawn(registry.clone().maintain(stopped(maintain_rx)));
    let app = crate::http::router(registry.clone(), web_root);
    let guard_registry = registry.clone();
    let stopper = async move {
        shutdown.await;
        let _ = maintain_stop.send(true);
        let _ = maintenance.await;
        registry.shutdown().await;
        let _ = stop_tx.send(true);
    };
    let grpc = tonic::transport::Server::builder()
        // Pings find clients that vanished without closing (their streams then end).
        .http2_keepalive_interval(Some(Duration::from_secs(20)))
        .http2_keepalive_timeout(Some(Duration::from_secs(10)))
        .layer(GuardLayer(guard_registry))
        .add_service(health)
        .add_service(reflection_v1)
        .add_service(reflection_v1alpha)
        .add_service(scenes)
        .add_service(lab)
        .serve_with_incoming_shutdown(
            // Answers go out as soon as they are written: with Nagle's algorithm a
            // reply of more than one segment (a SceneInfo with its scene document)
            // waited for the client's delayed acknowledgement, 40 ms on Linux.
            tonic::transport::server::TcpIncoming::from(listeners.grpc).with_nodelay(Some(true)),
            stopped(stop_rx.clone()),
        );
    let http = listeners.http.tap_io(|tcp| {
        if let Err(e) = tcp.set_nodelay(true) {
            tracing::debug!("TCP_NODELAY on an HTTP connection: {e}");
        }
    });
    let http = axum::serve(http, app).with_graceful_shutdown(stopped(stop_rx)).into_future();
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

/// The authentication a server runs with: `--auth`, and for `auto`, whether the
/// database has users. Serving a non-loopback address without authentication is
/// refused unless asked for with `--auth off`.
fn auth_mode(choice: AuthChoice, users: usize, listeners: &Listeners) -> anyhow::Result<AuthMode> {
    let mode = match choice {
        AuthChoice::Tokens => AuthMode::Tokens,
        AuthChoice::Off => AuthMode::SingleUser,
        AuthChoice::Auto if users > 0 => AuthMode::Tokens,
        AuthChoice::Auto => AuthMode::SingleUser,
    };
    let public = [&listeners.grpc, &listeners.http]
        .into_iter()
        .filter_map(|l| l.local_addr().ok())
        .find(|a| !a.ip().is_loopback());
    match (mode, public, choice) {
        (AuthMode::SingleUser, Some(addr), AuthChoice::Auto) => anyhow::bail!(
            "refusing to serve {addr} without authentication: add a user first (`floe admin user add NAME --admin`), \
             or pass --auth off to let anyone who reaches {addr} use the server"
        ),
        (AuthMode::SingleUser, Some(addr), _) => {
            tracing::warn!("serving {addr} WITHOUT authentication (--auth off): anyone who reaches it is an admin")
        }
        (AuthMode::Tokens, _, _) if users == 0 => {
            tracing::warn!("no users yet: every call is refused until `floe admin user add NAME --admin`")
        }
        _ => {}
    }
    Ok(mode)
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
        let listeners = Listeners { grpc, http };
        let location = args.store.location();
        if args.worker.is_some() && !location.database_url().starts_with("postgres") {
            anyhow::bail!("--worker needs a PostgreSQL --database shared by every worker (postgres://...)");
        }
        let store = Store::open(&location, args.worker.as_deref()).await?;
        let mode = auth_mode(args.auth, store.db.users().await?.len(), &listeners)?;
        tracing::info!(
            "data in {} (database {}); {}",
            location.data_dir.display(),
            location.database_display(),
            match mode {
                AuthMode::Tokens => "API tokens required",
                AuthMode::SingleUser => "single-user mode, no tokens",
            }
        );
        let web_root = args.web.clone().unwrap_or_else(default_web_root);
        if !web_root.join("index.html").exists() {
            tracing::warn!("no viewer at {} (pass --web DIR); the API still works", web_root.display());
        }
        let choice = args.backend.into();
        let backend = tokio::task::spawn_blocking(move || floe_gpu::select::select(choice)).await??;
        let member = match &args.worker {
            Some(name) => {
                let info = WorkerInfo {
                    name: name.clone(),
                    grpc: args.advertise_grpc.clone().unwrap_or(listeners.grpc.local_addr()?.to_string()),
                    http: args.advertise_http.clone().unwrap_or(listeners.http.local_addr()?.to_string()),
                    backend: backend.name.to_string(),
                    max_scenes: args.max_scenes,
                    max_particles: args.max_particles,
                };
                Some(Member::join(&store.db, info, Duration::from_secs(args.lease)).await?)
            }
            None => None,
        };
        let options = crate::service::Options { backend: backend.name, ..args.options(mode) };
        let registry = Registry::open(options, backend.factory, store, member).await?;
        let local = Caller::local();
        // A cluster's workers start with none: each would make its own.
        if args.worker.is_none()
            && args.scene != "none"
            && mode == AuthMode::SingleUser
            && registry.list(&local).is_empty()
        {
            // `auto`: the dam break sized to the backend; a named preset at its own size.
            let (preset, size) = match args.scene.as_str() {
                "auto" => ("dam_break".to_string(), PresetSize::Auto),
                name => (name.to_string(), PresetSize::Full),
            };
            let placing = crate::service::Placing { size: Some(size), ..Default::default() };
            let handle =
                registry.create_routed(&local, SceneSource::Preset(preset.clone()), Vec::new(), placing).await?;
            match handle.shared.sizing() {
                Some(c) => tracing::info!(
                    "default scene: the {preset} at {} particles, measured at {:.2} times real time on the {} \
                     backend (--scene {preset} for the full {})",
                    c.particles,
                    c.rtf,
                    backend.name,
                    c.full_particles
                ),
                None => tracing::info!("default scene '{preset}' is scene {}", handle.shared.id),
            }
        }
        tracing::info!(
            "gRPC (floe.v1.SceneService, floe.v1.LabService, health, reflection) on {}",
            listeners.grpc.local_addr()?
        );
        tracing::info!("REST and WebSocket API on http://{}/api/v1, metrics on /metrics", listeners.http.local_addr()?);
        println!("Floe viewer: http://{}/", listeners.http.local_addr()?);
        run(listeners, registry, web_root, signal()).await
    })
}

/// The viewer's files: `web/` of this source tree when it is there (a `cargo run`
/// from a checkout), else `web/` in the working directory.
fn default_web_root() -> PathBuf {
    let source = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../web");
    if source.join("index.html").exists() { source } else { PathBuf::from("web") }
}

#[cfg(test)]
mod tests {
    use super::*;

    async fn listeners(ip: &str) -> Listeners {
        Listeners {
            grpc: TcpListener::bind(format!("{ip}:0")).await.unwrap(),
            http: TcpListener::bind(format!("{ip}:0")).await.unwrap(),
        }
    }

    #[tokio::test]
    async fn no_authentication_only_on_loopback_unless_asked_for() {
        let (local, public) = (listeners("127.0.0.1").await, listeners("0.0.0.0").await);
        assert_eq!(auth_mode(AuthChoice::Auto, 0, &local).unwrap(), AuthMode::SingleUser);
        assert_eq!(auth_mode(AuthChoice::Auto, 2, &local).unwrap(), AuthMode::Tokens);
        let e = auth_mode(AuthChoice::Auto, 0, &public).unwrap_err().to_string();
        assert!(e.starts_with("refusing to serve 0.0.0.0:") && e.contains("floe admin user add"), "{e}");
        assert_eq!(auth_mode(AuthChoice::Auto, 1, &public).unwrap(), AuthMode::Tokens);
        assert_eq!(auth_mode(AuthChoice::Off, 0, &public).unwrap(), AuthMode::SingleUser);
        assert_eq!(auth_mode(AuthChoice::Tokens, 0, &local).unwrap(), AuthMode::Tokens);
    }
}
