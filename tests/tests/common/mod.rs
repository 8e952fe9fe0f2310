//! A real server on 127.0.0.1:0 for end-to-end tests, stopped on request.

#![allow(dead_code)]

use floe_server::service::Registry;
use std::net::SocketAddr;
use std::sync::Arc;
use tokio::sync::oneshot;

/// A running server.
pub struct TestServer {
    /// gRPC address.
    pub grpc: SocketAddr,
    /// HTTP address.
    pub http: SocketAddr,
    /// Its scenes, for tests that set up state directly.
    pub registry: Arc<Registry>,
    stop: Option<oneshot::Sender<()>>,
    task: tokio::task::JoinHandle<anyhow::Result<()>>,
}

/// An empty registry with the default limits whose scenes run on the CPU
/// backend (fast and deterministic; the GPU backend has its own tests).
pub fn cpu_registry() -> Arc<Registry> {
    Arc::new(Registry::new(Default::default(), Arc::new(floe_engine::simulation::cpu_backend)))
}

impl TestServer {
    /// Starts a server with no scenes.
    pub async fn start() -> Self {
        let grpc = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let http = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let (grpc_addr, http_addr) = (grpc.local_addr().unwrap(), http.local_addr().unwrap());
        let registry = cpu_registry();
        let (stop, stopped) = oneshot::channel::<()>();
        let task = tokio::spawn(floe_server::serve::run(
            floe_server::serve::Listeners { grpc, http },
            registry.clone(),
            "../web".into(),
            async {
                let _ = stopped.await;
            },
        ));
        Self { grpc: grpc_addr, http: http_addr, registry, stop: Some(stop), task }
    }

    /// `http://` URL of the gRPC listener.
    pub fn grpc_url(&self) -> String {
        format!("http://{}", self.grpc)
    }

    /// A connected channel to the gRPC listener.
    pub async fn channel(&self) -> tonic::transport::Channel {
        tonic::transport::Endpoint::from_shared(self.grpc_url()).unwrap().connect().await.unwrap()
    }

    /// Signals shutdown and waits until the server has stopped cleanly.
    pub async fn shutdown(mut self) {
        self.stop.take().unwrap().send(()).unwrap();
        self.task.await.unwrap().unwrap();
    }

    /// Signals shutdown without waiting.
    pub fn stop(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
    }

    /// Waits for a server already told to stop.
    pub async fn stopped(self) {
        self.task.await.unwrap().unwrap();
    }
}
