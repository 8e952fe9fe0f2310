//! The gRPC adapter: `floe.v1.SceneService` over the in-process [`Registry`].
//! Generated types stay here, in [`crate::grpc_lab`] and in [`crate::convert`]; the
//! service API does not see them. Every call arrives through [`crate::grpc_guard`],
//! which authenticated it and put its [`Caller`] in the request's extensions.

use crate::auth::Caller;
use crate::convert::{self, status};
use crate::service::{MAX_STEPS_PER_REQUEST, Need};
use crate::service::{Placing, Registry, SceneSource};
use floe_proto::pb::scene_service_server::SceneService;
use floe_proto::pb::{self, create_scene_request::Source};
use std::pin::Pin;
use std::sync::Arc;
use tokio_stream::Stream;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status};

/// A server stream of gRPC messages.
pub type Streamed<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send + 'static>>;

/// The gRPC service.
#[derive(Debug, Clone)]
pub struct Grpc {
    registry: Arc<Registry>,
}

impl Grpc {
    /// A service over `registry`.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self { registry }
    }
}

/// The caller [`crate::grpc_guard`] authenticated; a request that did not pass the
/// guard is refused rather than trusted.
pub fn caller<T>(request: &Request<T>) -> Result<Caller, Status> {
    request
        .extensions()
        .get::<Caller>()
        .cloned()
        .ok_or_else(|| Status::unauthenticated("the call was not authenticated"))
}

type Reply<T> = Result<Response<T>, Status>;

#[tonic::async_trait]
impl SceneService for Grpc {
    async fn create_scene(&self, request: Request<pb::CreateSceneRequest>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let named =
            request.metadata().get(crate::cluster::WORKER_HEADER).and_then(|v| v.to_str().ok()).map(String::from);
        let r = request.into_inner();
        let source = match r.source {
            Some(Source::Preset(name)) => SceneSource::Preset(name),
            Some(Source::Document(text)) => {
                SceneSource::Document { text, format: convert::document_format(&r.document_format)? }
            }
            None => return Err(Status::invalid_argument("source: give a preset name or a scene document")),
        };
        let placing = Placing { worker: named.as_deref(), backend: Some(&r.backend), size: None };
        let handle = self.registry.create_routed(&who, source, r.overrides, placing).await.map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared, self.registry.worker_name())))
    }

    async fn get_scene(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let handle = self.registry.get(&who, request.into_inner().scene_id, Need::Watch).map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared, self.registry.worker_name())))
    }

    async fn list_scenes(&self, request: Request<pb::ListScenesRequest>) -> Reply<pb::ListScenesResponse> {
        let who = caller(&request)?;
        let mut scenes: Vec<_> = self
            .registry
            .list(&who)
            .iter()
            .map(|h| convert::scene_info(&h.shared, self.registry.worker_name()))
            .collect();
        scenes.extend(self.registry.placed_elsewhere(&who).iter().map(convert::placed_info));
        scenes.sort_by_key(|s| s.scene_id);
        Ok(Response::new(pb::ListScenesResponse { scenes }))
    }

    async fn list_presets(&self, request: Request<pb::ListPresetsRequest>) -> Reply<pb::ListPresetsResponse> {
        caller(&request)?;
        let presets = floe_engine::module::presets()
            .iter()
            .map(|p| pb::PresetInfo { name: p.name.into(), about: p.about.into() })
            .collect();
        Ok(Response::new(pb::ListPresetsResponse { presets }))
    }

    async fn delete_scene(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let handle = self.registry.delete(&who, request.into_inner().scene_id).await.map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared, self.registry.worker_name())))
    }

    async fn step(&self, request: Request<pb::StepRequest>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let r = request.into_inner();
        let until = if r.until_time != 0.0 {
            if !r.until_time.is_finite() || r.until_time < 0.0 {
                return Err(Status::invalid_argument(format!(
                    "until_time: must be a time >= 0 s, got {}",
                    r.until_time
                )));
            }
            Some(r.until_time)
        } else {
            if r.steps == 0 || r.steps > MAX_STEPS_PER_REQUEST {
                return Err(Status::invalid_argument(format!(
                    "steps: must be between 1 and {MAX_STEPS_PER_REQUEST}, got {}",
                    r.steps
                )));
            }
            None
        };
        self.registry.step(&who, r.scene_id, r.steps, until).await.map_err(status)?;
        self.info(&who, r.scene_id)
    }

    async fn run(&self, request: Request<pb::RunRequest>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let r = request.into_inner();
        if !r.real_time_factor.is_finite() || r.real_time_factor < 0.0 {
            return Err(Status::invalid_argument(format!(
                "real_time_factor: must be >= 0 (0 = as fast as possible), got {}",
                r.real_time_factor
            )));
        }
        self.registry.run(&who, r.scene_id, r.real_time_factor).await.map_err(status)?;
        self.info(&who, r.scene_id)
    }

    async fn pause(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        self.registry.pause(&who, id).await.map_err(status)?;
        self.info(&who, id)
    }

    async fn reset(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        self.registry.reset(&who, id).await.map_err(status)?;
        self.info(&who, id)
    }

    async fn get_stats(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneStats> {
        let who = caller(&request)?;
        let handle = self.registry.get(&who, request.into_inner().scene_id, Need::Watch).map_err(status)?;
        Ok(Response::new(convert::scene_stats(&handle.shared, self.registry.worker_name())))
    }

    async fn set_parameters(&self, request: Request<pb::SetParametersRequest>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let r = request.into_inner();
        self.registry.set_parameters(&who, r.scene_id, r.overrides).await.map_err(status)?;
        self.info(&who, r.scene_id)
    }

    async fn snapshot(&self, request: Request<pb::SceneRef>) -> Reply<pb::SceneSnapshot> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        let handle = self.registry.get(&who, id, Need::Steer).map_err(status)?;
        let state = handle.save().await.map_err(|e| status(e.into()))?;
        Ok(Response::new(pb::SceneSnapshot { scene_id: id, state }))
    }

    async fn restore(&self, request: Request<pb::RestoreRequest>) -> Reply<pb::SceneInfo> {
        let who = caller(&request)?;
        let r = request.into_inner();
        self.registry.restore(&who, r.scene_id, r.state).await.map_err(status)?;
        self.info(&who, r.scene_id)
    }

    type StreamFramesStream = Streamed<pb::Frame>;

    async fn stream_frames(&self, request: Request<pb::StreamFramesRequest>) -> Reply<Self::StreamFramesStream> {
        let who = caller(&request)?;
        let r = request.into_inner();
        let request = convert::frame_request(&r)?;
        let feed = self.registry.subscribe(&who, r.scene_id, &request).map_err(status)?;
        let frames = feed.spawn(frame_message);
        Ok(Response::new(Box::pin(ReceiverStream::new(frames))))
    }

    type WatchFramesStream = Streamed<pb::Frame>;

    async fn watch_frames(
        &self,
        request: Request<tonic::Streaming<pb::WatchFramesRequest>>,
    ) -> Reply<Self::WatchFramesStream> {
        use pb::watch_frames_request::Kind;
        let who = caller(&request)?;
        let mut inbound = request.into_inner();
        let start = match inbound.message().await? {
            Some(pb::WatchFramesRequest { kind: Some(Kind::Start(r)) }) => r,
            _ => return Err(Status::invalid_argument("start: the first request of WatchFrames must be a start")),
        };
        let feed = self.registry.subscribe(&who, start.scene_id, &convert::frame_request(&start)?).map_err(status)?;
        let control = feed.view_control();
        let mut frames = feed.spawn(frame_message);
        let (tx, rx) = tokio::sync::mpsc::channel(1);
        tokio::spawn(async move {
            let mut open = true;
            loop {
                let change = tokio::select! {
                    frame = frames.recv() => {
                        let Some(f) = frame else { break };
                        if tx.send(f).await.is_err() {
                            break;
                        }
                        continue;
                    }
                    m = inbound.message(), if open => m,
                };
                let refused = match change {
                    Ok(Some(pb::WatchFramesRequest { kind: Some(Kind::View(v)) })) => {
                        convert::view_request(&v).and_then(|r| control.set(&r).map_err(status)).err()
                    }
                    Ok(Some(_)) => {
                        Some(Status::invalid_argument("view: a later request of WatchFrames must be a view"))
                    }
                    // The client closed its side (or the call broke): no more views.
                    Ok(None) | Err(_) => {
                        open = false;
                        None
                    }
                };
                if let Some(e) = refused {
                    let _ = tx.send(Err(e)).await;
                    break;
                }
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }

    type StreamEventsStream = Streamed<pb::SceneEvent>;

    async fn stream_events(&self, request: Request<pb::SceneRef>) -> Reply<Self::StreamEventsStream> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        let feed = self.registry.events(&who, id).map_err(status)?;
        let events = feed.spawn(move |e| Ok(convert::scene_event(id, e)));
        Ok(Response::new(Box::pin(ReceiverStream::new(events))))
    }
}

/// A frame as its message.
fn frame_message(
    frame: Result<crate::service::frames::EncodedFrame, floe_proto::EncodeError>,
) -> Result<pb::Frame, Status> {
    frame
        .map(|f| pb::Frame { data: f.data.as_ref().clone(), sequence: f.sequence, skipped: f.skipped })
        .map_err(|e| Status::internal(e.to_string()))
}

impl Grpc {
    /// The `SceneInfo` of a scene after a call changed it.
    fn info(&self, who: &Caller, id: u64) -> Reply<pb::SceneInfo> {
        let handle = self.registry.get(who, id, Need::Watch).map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared, self.registry.worker_name())))
    }
}
