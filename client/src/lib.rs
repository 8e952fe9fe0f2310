//! # floe-client
//!
//! A typed async client for a Floe server over gRPC (`floe.v1.SceneService`),
//! with frames decoded into position arrays.
//!
//! ```no_run
//! # async fn demo() -> Result<(), floe_client::ClientError> {
//! let mut floe = floe_client::Client::connect("http://127.0.0.1:50051").await?;
//! let scene = floe.create_preset("dam_break", &["particle_spacing=0.025"]).await?;
//! floe.step(scene.scene_id, 100).await?;
//! let mut frames = floe.frames(scene.scene_id, floe_client::FrameRequest::default()).await?;
//! if let Some(frame) = frames.next().await? {
//!     println!("t = {} s, {} particles", frame.header.time, frame.positions.len());
//! }
//! # Ok(()) }
//! ```
//!
//! - [`Client`]: the calls ([`lab`]: checkpoints, share links, users and quotas).
//!   [`Frames`]: a decoded frame stream. [`recording`]: frames to and from files.
//! - [`route`]: following a scene to its worker in a cluster.
//! - [`cli`]: the `floectl` command line; [`top`]: `floectl top`'s table.

pub mod cli;
pub mod lab;
pub mod recording;
pub mod route;
pub mod top;

use floe_proto::pb::lab_service_client::LabServiceClient;
use floe_proto::pb::scene_service_client::SceneServiceClient;
use floe_proto::pb::{self, create_scene_request::Source};
use floe_proto::{ChannelKind, Decoder, Frame, Limits, Particles};
use tonic::metadata::{Ascii, MetadataValue};
use tonic::service::interceptor::InterceptedService;
use tonic::transport::Channel;

pub use floe_proto::pb::{SceneInfo, SceneStats};

/// What went wrong talking to a server. Each message says it all once: `Connect` leaves its
/// cause to [`std::error::Error::source`], the others hold no source, so a printed error chain
/// (`anyhow`'s `{:#}`) does not repeat itself.
#[derive(Debug, thiserror::Error)]
pub enum ClientError {
    /// Could not connect.
    #[error("cannot connect to {address}")]
    Connect {
        /// The address.
        address: String,
        /// The cause.
        source: tonic::transport::Error,
    },
    /// The server refused the call; the message names what was wrong.
    #[error("{} ({:?})", .0.message(), .0.code())]
    Status(tonic::Status),
    /// A frame could not be decoded.
    #[error("frame: {0}")]
    Decode(floe_proto::DecodeError),
    /// The token cannot be sent as a header (it is not printable ASCII).
    #[error("the token is not a valid header value (printable ASCII only)")]
    BadToken,
}

impl From<tonic::Status> for ClientError {
    fn from(status: tonic::Status) -> Self {
        ClientError::Status(status)
    }
}

impl From<floe_proto::DecodeError> for ClientError {
    fn from(e: floe_proto::DecodeError) -> Self {
        ClientError::Decode(e)
    }
}

/// Options of a frame stream.
#[derive(Debug, Clone)]
pub struct FrameRequest {
    /// Extra channels by name (the scene's `SceneInfo::channels` lists them), e.g. `velocity`.
    pub channels: Vec<String>,
    /// The particle set (`SceneInfo::sets`); empty for the scene's SPH particles.
    pub set: String,
    /// Most frames per second.
    pub max_fps: f64,
    /// Bits per position axis, 8 to 16.
    pub position_bits: u32,
    /// Identity-ordered (particle i stays i) rather than unordered.
    pub identity: bool,
    /// Send every n-th particle; 1 sends all.
    pub decimation: u32,
    /// A region of interest and a particle budget per frame (`None`: every particle).
    pub view: Option<pb::FrameView>,
}

impl Default for FrameRequest {
    fn default() -> Self {
        Self {
            channels: Vec::new(),
            set: String::new(),
            max_fps: 30.0,
            position_bits: 16,
            identity: true,
            decimation: 1,
            view: None,
        }
    }
}

/// Adds `authorization: Bearer <token>` to every call, when there is a token.
#[derive(Debug, Clone)]
pub struct Bearer(Option<MetadataValue<Ascii>>);

impl tonic::service::Interceptor for Bearer {
    fn call(&mut self, mut request: tonic::Request<()>) -> Result<tonic::Request<()>, tonic::Status> {
        if let Some(v) = &self.0 {
            request.metadata_mut().insert("authorization", v.clone());
        }
        Ok(request)
    }
}

/// A channel whose calls carry the token.
type Authed = InterceptedService<Channel, Bearer>;

/// A connection to a Floe server.
#[derive(Debug, Clone)]
pub struct Client {
    inner: SceneServiceClient<Authed>,
    lab: LabServiceClient<Authed>,
    /// Each scene's worker in a cluster.
    routes: route::Routes,
    /// The backend new scenes ask for; empty: any.
    backend: String,
}

/// Largest message the client accepts (bytes): snapshots of large scenes.
const MAX_MESSAGE_BYTES: usize = 512 << 20;
/// HTTP/2 receive window per stream (bytes): a few frames of a large scene.
const STREAM_WINDOW_BYTES: u32 = 4 << 20;

impl Client {
    /// Connects to `address`, e.g. `http://127.0.0.1:50051`, without a token (a
    /// single-user server).
    pub async fn connect(address: &str) -> Result<Self, ClientError> {
        Self::connect_with_token(address, None).await
    }

    /// Connects to `address`; every call carries `token` (an API token or a share
    /// link's token) when given.
    pub async fn connect_with_token(address: &str, token: Option<&str>) -> Result<Self, ClientError> {
        let bearer = match token {
            Some(t) => Some(format!("Bearer {t}").parse().map_err(|_| ClientError::BadToken)?),
            None => None,
        };
        let err = |source| ClientError::Connect { address: address.into(), source };
        // Frames of large scenes are hundreds of kB: HTTP/2's default 64 kB receive
        // window would make the server wait for window updates within every frame.
        let channel = tonic::transport::Endpoint::from_shared(address.to_owned())
            .map_err(err)?
            .initial_stream_window_size(Some(STREAM_WINDOW_BYTES))
            .initial_connection_window_size(Some(2 * STREAM_WINDOW_BYTES))
            .connect()
            .await
            .map_err(err)?;
        let authed = InterceptedService::new(channel, Bearer(bearer));
        Ok(Self {
            inner: SceneServiceClient::new(authed.clone()).max_decoding_message_size(MAX_MESSAGE_BYTES),
            lab: LabServiceClient::new(authed),
            routes: route::Routes::default(),
            backend: String::new(),
        })
    }

    /// Scenes this client creates from now on must run on `backend`: `"gpu"`,
    /// `"cpu"`, or `""` for any (the default). A single server refuses a backend it
    /// does not run; a cluster places the scene on a worker that runs it.
    pub fn set_backend(&mut self, backend: &str) {
        self.backend = backend.to_owned();
    }

    /// Creates a scene from a preset with `key=value` overrides.
    pub async fn create_preset(&mut self, preset: &str, overrides: &[&str]) -> Result<SceneInfo, ClientError> {
        self.create(Source::Preset(preset.into()), "", overrides).await
    }

    /// Creates a scene from a document (`format`: "toml" or "json").
    pub async fn create_document(
        &mut self,
        text: &str,
        format: &str,
        overrides: &[&str],
    ) -> Result<SceneInfo, ClientError> {
        self.create(Source::Document(text.into()), format, overrides).await
    }

    async fn create(&mut self, source: Source, format: &str, overrides: &[&str]) -> Result<SceneInfo, ClientError> {
        let req = pb::CreateSceneRequest {
            source: Some(source),
            document_format: format.into(),
            overrides: overrides.iter().map(|s| s.to_string()).collect(),
            backend: self.backend.clone(),
        };
        let info: SceneInfo = routed!(self.routes, self.inner, create_scene, None, false, req)?;
        // The worker that built it holds it; the next new scene is placed afresh.
        self.routes.forget(None);
        if !info.worker.is_empty() {
            self.routes.remember(Some(info.scene_id), info.worker.clone());
        }
        Ok(info)
    }

    /// One scene.
    pub async fn get(&mut self, scene_id: u64) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, get_scene, Some(scene_id), true, pb::SceneRef { scene_id })
    }

    /// Every scene.
    pub async fn list(&mut self) -> Result<Vec<SceneInfo>, ClientError> {
        Ok(routed!(self.routes, self.inner, list_scenes, None, true, pb::ListScenesRequest {})?.scenes)
    }

    /// The built-in presets `create_preset` takes, as (name, one line on what it is).
    pub async fn presets(&mut self) -> Result<Vec<(String, String)>, ClientError> {
        let list = routed!(self.routes, self.inner, list_presets, None, true, pb::ListPresetsRequest {})?;
        Ok(list.presets.into_iter().map(|p| (p.name, p.about)).collect())
    }

    /// Deletes a scene.
    pub async fn delete(&mut self, scene_id: u64) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, delete_scene, Some(scene_id), false, pb::SceneRef { scene_id })
    }

    /// Steps a paused scene `steps` times.
    pub async fn step(&mut self, scene_id: u64, steps: u64) -> Result<SceneInfo, ClientError> {
        routed!(
            self.routes,
            self.inner,
            step,
            Some(scene_id),
            false,
            pb::StepRequest { scene_id, steps, until_time: 0.0 }
        )
    }

    /// Steps a paused scene until simulated time `t` (s).
    pub async fn step_until(&mut self, scene_id: u64, t: f64) -> Result<SceneInfo, ClientError> {
        routed!(
            self.routes,
            self.inner,
            step,
            Some(scene_id),
            false,
            pb::StepRequest { scene_id, steps: 0, until_time: t }
        )
    }

    /// Runs continuously at `real_time_factor` (0: as fast as possible).
    pub async fn run(&mut self, scene_id: u64, real_time_factor: f64) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, run, Some(scene_id), false, pb::RunRequest { scene_id, real_time_factor })
    }

    /// Pauses.
    pub async fn pause(&mut self, scene_id: u64) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, pause, Some(scene_id), false, pb::SceneRef { scene_id })
    }

    /// Puts a paused or halted scene back at t = 0 with its current settings.
    pub async fn reset(&mut self, scene_id: u64) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, reset, Some(scene_id), false, pb::SceneRef { scene_id })
    }

    /// Throughput and streaming statistics.
    pub async fn stats(&mut self, scene_id: u64) -> Result<SceneStats, ClientError> {
        routed!(self.routes, self.inner, get_stats, Some(scene_id), true, pb::SceneRef { scene_id })
    }

    /// Changes tunable settings (`key=value` overrides, e.g. `gravity=[0,-1,0]`).
    pub async fn set_parameters(&mut self, scene_id: u64, overrides: &[&str]) -> Result<SceneInfo, ClientError> {
        let overrides = overrides.iter().map(|s| s.to_string()).collect();
        routed!(
            self.routes,
            self.inner,
            set_parameters,
            Some(scene_id),
            false,
            pb::SetParametersRequest { scene_id, overrides }
        )
    }

    /// The full state as bytes.
    pub async fn snapshot(&mut self, scene_id: u64) -> Result<Vec<u8>, ClientError> {
        Ok(routed!(self.routes, self.inner, snapshot, Some(scene_id), true, pb::SceneRef { scene_id })?.state)
    }

    /// Restores a paused scene from [`Client::snapshot`] bytes.
    pub async fn restore(&mut self, scene_id: u64, state: Vec<u8>) -> Result<SceneInfo, ClientError> {
        routed!(self.routes, self.inner, restore, Some(scene_id), false, pb::RestoreRequest { scene_id, state })
    }

    /// A stream of decoded frames. The scene's channel list is read first, so frames
    /// convert to [`Particles`] with every channel under its name ([`Frames::particles`]).
    /// In a cluster the stream follows the scene when it moves to another worker.
    pub async fn frames(&mut self, scene_id: u64, r: FrameRequest) -> Result<Frames, ClientError> {
        let scene = self.get(scene_id).await?;
        let request = stream_request(scene_id, r);
        let stream = routed!(self.routes, self.inner, stream_frames, Some(scene_id), true, request.clone())?;
        Ok(Frames {
            stream,
            decoder: Decoder::new(Limits::default()),
            scene,
            client: self.clone(),
            request,
            views: None,
        })
    }

    /// As [`Client::frames`], on a stream whose view ([`FrameRequest::view`]) changes
    /// while it is open ([`Frames::set_view`]): a viewer whose camera moves.
    pub async fn watch_frames(&mut self, scene_id: u64, r: FrameRequest) -> Result<Frames, ClientError> {
        let scene = self.get(scene_id).await?;
        let request = stream_request(scene_id, r);
        let (stream, views) = self.watch(&request).await?;
        let views = Some(views);
        Ok(Frames { stream, decoder: Decoder::new(Limits::default()), scene, client: self.clone(), request, views })
    }

    /// Opens `WatchFrames` with `request` as its start, on the scene's worker.
    async fn watch(
        &mut self,
        request: &pb::StreamFramesRequest,
    ) -> Result<(tonic::Streaming<pb::Frame>, ViewSender), ClientError> {
        let target = Some(request.scene_id);
        let mut attempt = route::Routes::attempt(target, true);
        loop {
            let (tx, rx) = tokio::sync::mpsc::channel(4);
            let start = pb::WatchFramesRequest { kind: Some(pb::watch_frames_request::Kind::Start(request.clone())) };
            tx.send(start).await.expect("the receiver is held here");
            let outbound = tokio_stream::wrappers::ReceiverStream::new(rx);
            match self.inner.watch_frames(self.routes.request(target, outbound)).await {
                Ok(response) => return Ok((response.into_inner(), tx)),
                Err(status) => {
                    if !self.routes.again(&mut attempt, &status).await {
                        return Err(ClientError::Status(status));
                    }
                }
            }
        }
    }

    /// The scene's events (halted, deleted).
    pub async fn events(&mut self, scene_id: u64) -> Result<tonic::Streaming<pb::SceneEvent>, ClientError> {
        routed!(self.routes, self.inner, stream_events, Some(scene_id), true, pb::SceneRef { scene_id })
    }
}

/// Sends a watched stream's later requests.
type ViewSender = tokio::sync::mpsc::Sender<pb::WatchFramesRequest>;

/// The request of a frame stream.
fn stream_request(scene_id: u64, r: FrameRequest) -> pb::StreamFramesRequest {
    pb::StreamFramesRequest {
        scene_id,
        channels: Vec::new(),
        max_fps: r.max_fps,
        position_bits: r.position_bits,
        mode: if r.identity { pb::FrameMode::Identity } else { pb::FrameMode::Unordered } as i32,
        decimation: r.decimation,
        channel_names: r.channels,
        particle_set: r.set,
        view: r.view,
    }
}

/// Decoded frames of one scene, in order.
#[derive(Debug)]
pub struct Frames {
    stream: tonic::Streaming<pb::Frame>,
    decoder: Decoder,
    /// The scene, for its channels' and sets' names.
    scene: SceneInfo,
    /// To subscribe again when the scene moves to another worker.
    client: Client,
    request: pb::StreamFramesRequest,
    /// A watched stream's later requests ([`Client::watch_frames`]).
    views: Option<ViewSender>,
}

impl Frames {
    /// The next frame, decoded; `None` when the stream ends (scene deleted, server stopped).
    pub async fn next(&mut self) -> Result<Option<Frame>, ClientError> {
        Ok(match self.next_raw().await? {
            Some(bytes) => Some(self.decoder.decode(&bytes)?),
            None => None,
        })
    }

    /// The next frame as the server encoded it (for recording). A stream that breaks
    /// (its worker stopped) or ends while the scene lives on (it moved to another
    /// worker) is opened again where the scene is now, starting with a whole frame.
    pub async fn next_raw(&mut self) -> Result<Option<Vec<u8>>, ClientError> {
        loop {
            let lost = match self.stream.message().await {
                Ok(Some(f)) => return Ok(Some(f.data)),
                Ok(None) => None,
                Err(status) if answered(&status) => return Err(status.into()),
                Err(status) => Some(status),
            };
            let scene_id = self.request.scene_id;
            match self.client.get(scene_id).await {
                Ok(_) => {}
                Err(ClientError::Status(s)) if lost.is_none() && s.code() == tonic::Code::NotFound => return Ok(None),
                Err(e) => return Err(lost.map_or(e, ClientError::Status)),
            }
            let client = &mut self.client;
            if self.views.is_some() {
                let (stream, views) = client.watch(&self.request).await?;
                (self.stream, self.views) = (stream, Some(views));
            } else {
                self.stream =
                    routed!(client.routes, client.inner, stream_frames, Some(scene_id), true, self.request.clone())?;
            }
            self.decoder = Decoder::new(Limits::default());
        }
    }

    /// Changes a watched stream's view from the next frame on (`None`: every particle
    /// again). A bad view ends the stream with INVALID_ARGUMENT naming the field, read
    /// at the next [`Frames::next`]. Only for [`Client::watch_frames`] streams.
    pub async fn set_view(&mut self, view: Option<pb::FrameView>) -> Result<(), ClientError> {
        let Some(views) = &self.views else {
            return Err(ClientError::Status(tonic::Status::failed_precondition(
                "set_view: this stream's view is fixed; open it with watch_frames",
            )));
        };
        let message = view.clone().unwrap_or_default();
        let request = pb::WatchFramesRequest { kind: Some(pb::watch_frames_request::Kind::View(message)) };
        // A stream whose call ended has no reader: the next frame read says why.
        let _ = views.send(request).await;
        self.request.view = view;
        Ok(())
    }

    /// `frame`'s positions and channels under the scene's names.
    pub fn particles(&self, frame: Frame) -> Particles {
        particles(frame, Some(&self.scene))
    }
}

/// Whether a stream's error is the server's answer (the request or the caller was
/// refused), not a lost connection.
fn answered(status: &tonic::Status) -> bool {
    use tonic::Code;
    matches!(
        status.code(),
        Code::NotFound
            | Code::InvalidArgument
            | Code::PermissionDenied
            | Code::Unauthenticated
            | Code::ResourceExhausted
            | Code::FailedPrecondition
            | Code::OutOfRange
    )
}

/// `frame`'s positions and channels, each channel under its name in `scene`'s channel
/// list, else the channel table's name (`channel <tag>` for a per-scene tag it lacks);
/// the set under its name in `scene`, else `particles` for set 0 and `set <index>` otherwise.
pub fn particles(frame: Frame, scene: Option<&SceneInfo>) -> Particles {
    let name = |kind: ChannelKind| {
        let named = scene.and_then(|s| s.channels.iter().find(|c| c.tag == u32::from(kind.tag())));
        named.map_or_else(|| kind.name(), |c| c.name.clone())
    };
    let index = u32::from(frame.header.set);
    let set = scene.and_then(|s| s.sets.iter().find(|x| x.index == index)).map(|x| x.name.clone());
    Particles {
        set: set.unwrap_or_else(|| if index == 0 { "particles".into() } else { format!("set {index}") }),
        positions: frame.positions,
        channels: frame.channels.into_iter().map(|(kind, values)| (name(kind), values)).collect(),
        grid: frame.grid,
        ids: frame.ids,
    }
}
