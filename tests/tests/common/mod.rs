//! A real server on 127.0.0.1:0 for end-to-end tests, stopped on request: kept in
//! memory in single-user mode ([`TestServer::start`]), or a lab server with users,
//! tokens and a data directory ([`Lab::start`]).

#![allow(dead_code)]

use floe_server::auth::AuthMode;
use floe_server::service::{Options, Registry};
use floe_server::store::{Location, Store};
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
    /// Starts a single-user server with no scenes, kept in memory.
    pub async fn start() -> Self {
        Self::start_with(cpu_registry()).await
    }

    /// Starts a server over `registry`.
    pub async fn start_with(registry: Arc<Registry>) -> Self {
        let grpc = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let http = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let (grpc_addr, http_addr) = (grpc.local_addr().unwrap(), http.local_addr().unwrap());
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

/// A lab server: API tokens required, SQLite in a temporary data directory, scenes on
/// the CPU backend.
pub struct Lab {
    /// The server.
    pub server: TestServer,
    /// Its data directory.
    pub dir: tempfile::TempDir,
    /// (user, token) of each user, in the order given.
    pub users: Vec<(String, String)>,
    options: Options,
}

/// A registry over the data in `dir` (SQLite), authenticating with tokens.
async fn lab_registry(dir: &std::path::Path, options: Options) -> Arc<Registry> {
    let location = Location { data_dir: dir.to_path_buf(), database: None };
    let store = Store::open(&location, None).await.unwrap();
    let options = Options { auth: AuthMode::Tokens, ..options };
    Registry::open(options, Arc::new(floe_engine::simulation::cpu_backend), store, None).await.unwrap()
}

impl Lab {
    /// Starts a lab server with these users (name, admin) and options (auth is tokens).
    pub async fn start(users: &[(&str, bool)], options: Options) -> Self {
        let dir = tempfile::tempdir().unwrap();
        let location = Location { data_dir: dir.path().to_path_buf(), database: None };
        let db = location.open_database().await.unwrap();
        let mut tokens = Vec::new();
        for &(name, admin) in users {
            tokens.push((name.to_string(), floe_server::admin::add_user(&db, name, admin).await.unwrap()));
        }
        db.close().await;
        let registry = lab_registry(dir.path(), options.clone()).await;
        Self { server: TestServer::start_with(registry).await, dir, users: tokens, options }
    }

    /// Shuts the server down gracefully and starts a new one on the same data.
    pub async fn restart(self) -> Self {
        let Self { server, dir, users, options } = self;
        server.shutdown().await;
        let registry = lab_registry(dir.path(), options.clone()).await;
        Self { server: TestServer::start_with(registry).await, dir, users, options }
    }

    /// The token of `user`.
    pub fn token(&self, user: &str) -> &str {
        &self.users.iter().find(|u| u.0 == user).expect("a user of this lab").1
    }

    /// A gRPC client calling as `user`.
    pub async fn client(&self, user: &str) -> floe_client::Client {
        floe_client::Client::connect_with_token(&self.server.grpc_url(), Some(self.token(user))).await.unwrap()
    }
}

/// An HTTP/1.1 answer: status, headers (lower-case names) and body.
pub struct Answer {
    /// Status code.
    pub status: u16,
    /// Headers.
    pub headers: Vec<(String, String)>,
    /// Body bytes.
    pub body: Vec<u8>,
}

impl Answer {
    /// The body as JSON (`null` when it is not JSON).
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body).unwrap_or(serde_json::Value::Null)
    }

    /// The API error message, or a placeholder saying there is none.
    pub fn error(&self) -> String {
        self.json()["error"].as_str().unwrap_or("(no JSON error)").to_owned()
    }

    /// A header's value.
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers.iter().find(|h| h.0 == name).map(|h| h.1.as_str())
    }
}

/// Sends one raw HTTP/1.1 request (`Connection: close`) to `addr` and reads the answer:
/// a real socket, so the server's own HTTP handling (limits, errors) is what answers.
pub async fn http(addr: SocketAddr, method: &str, path: &str, headers: &[(&str, &str)], body: &str) -> Answer {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut s = tokio::net::TcpStream::connect(addr).await.unwrap();
    let mut req = format!("{method} {path} HTTP/1.1\r\nhost: {addr}\r\nconnection: close\r\n");
    for (k, v) in headers {
        req += &format!("{k}: {v}\r\n");
    }
    if !body.is_empty() {
        req += &format!("content-type: application/json\r\ncontent-length: {}\r\n", body.len());
    }
    req += "\r\n";
    req += body;
    s.write_all(req.as_bytes()).await.unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).await.unwrap();
    let split = raw.windows(4).position(|w| w == b"\r\n\r\n").expect("a complete head");
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let mut lines = head.lines();
    let status = lines.next().unwrap().split(' ').nth(1).unwrap().parse().unwrap();
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_owned()))
        .collect();
    let mut body = raw[split + 4..].to_vec();
    if headers.iter().any(|h| h.0 == "transfer-encoding" && h.1.contains("chunked")) {
        body = dechunk(&body);
    }
    Answer { status, headers, body }
}

fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    while let Some(end) = data.windows(2).position(|w| w == b"\r\n") {
        let size = usize::from_str_radix(std::str::from_utf8(&data[..end]).unwrap().trim(), 16).unwrap();
        if size == 0 {
            break;
        }
        out.extend_from_slice(&data[end + 2..end + 2 + size]);
        data = &data[end + 4 + size..];
    }
    out
}

/// The gRPC code of a client error.
pub fn code(e: &floe_client::ClientError) -> tonic::Code {
    match e {
        floe_client::ClientError::Status(s) => s.code(),
        other => panic!("not a status: {other}"),
    }
}

/// A WebSocket handshake request for `url`, offering `token` as a protocol when given.
pub fn ws_request(url: &str, token: Option<&str>) -> tokio_tungstenite::tungstenite::handshake::client::Request {
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;
    let mut req = url.into_client_request().unwrap();
    let protocols = match token {
        Some(t) => format!("floe.v1, {t}"),
        None => "floe.v1".to_owned(),
    };
    req.headers_mut().insert("sec-websocket-protocol", protocols.parse().unwrap());
    req
}
