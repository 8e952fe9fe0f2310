//! The gRPC adapter: `floe.v1.SceneService` over the in-process [`Registry`].
//! Generated types stay here and in [`crate::convert`]; the service API does
//! not see them.

use crate::convert::{self, status};
use crate::service::{CommandError, Event, MAX_STEPS_PER_REQUEST};
use crate::service::{Registry, SceneSource, ServiceError};
use floe_proto::pb::scene_service_server::SceneService;
use floe_proto::pb::{self, create_scene_request::Source};
use std::pin::Pin;
use std::sync::Arc;
use tokio::sync::mpsc;
use tokio_stream::Stream;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status};

/// A server stream of gRPC messages.
type Streamed<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send + 'static>>;

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

#[tonic::async_trait]
impl SceneService for Grpc {
    async fn create_scene(&self, request: Request<pb::CreateSceneRequest>) -> Result<Response<pb::SceneInfo>, Status> {
        let r = request.into_inner();
        let source = match r.source {
            Some(Source::Preset(name)) => SceneSource::Preset(name),
            Some(Source::Document(text)) => {
                SceneSource::Document { text, format: convert::document_format(&r.document_format)? }
            }
            None => return Err(Status::invalid_argument("source: give a preset name or a scene document")),
        };
        let registry = self.registry.clone();
        // Building samples every particle: off the async workers.
        let handle = tokio::task::spawn_blocking(move || registry.create(source, &r.overrides))
            .await
            .map_err(|e| Status::internal(e.to_string()))?
            .map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn get_scene(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneInfo>, Status> {
        let handle = self.registry.get(request.into_inner().scene_id).map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn list_scenes(&self, _: Request<pb::ListScenesRequest>) -> Result<Response<pb::ListScenesResponse>, Status> {
        let scenes = self.registry.list().iter().map(|h| convert::scene_info(&h.shared)).collect();
        Ok(Response::new(pb::ListScenesResponse { scenes }))
    }

    async fn delete_scene(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneInfo>, Status> {
        let id = request.into_inner().scene_id;
        let registry = self.registry.clone();
        let handle = tokio::task::spawn_blocking(move || registry.delete(id))
            .await
            .map_err(|e| Status::internal(e.to_string()))?
            .map_err(status)?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn step(&self, request: Request<pb::StepRequest>) -> Result<Response<pb::SceneInfo>, Status> {
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
        let handle = self.registry.get(r.scene_id).map_err(status)?;
        handle.step(r.steps, until).await.map_err(|e| status(ServiceError::FailedPrecondition(e.to_string())))?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn run(&self, request: Request<pb::RunRequest>) -> Result<Response<pb::SceneInfo>, Status> {
        let r = request.into_inner();
        if !r.real_time_factor.is_finite() || r.real_time_factor < 0.0 {
            return Err(Status::invalid_argument(format!(
                "real_time_factor: must be >= 0 (0 = as fast as possible), got {}",
                r.real_time_factor
            )));
        }
        let handle = self.registry.get(r.scene_id).map_err(status)?;
        handle.run(r.real_time_factor).await.map_err(|e| status(ServiceError::FailedPrecondition(e.to_string())))?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn pause(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneInfo>, Status> {
        let handle = self.registry.get(request.into_inner().scene_id).map_err(status)?;
        handle.pause().await.map_err(|e| status(ServiceError::FailedPrecondition(e.to_string())))?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn reset(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneInfo>, Status> {
        let handle = self.registry.get(request.into_inner().scene_id).map_err(status)?;
        handle.reset().await.map_err(|e| status(ServiceError::FailedPrecondition(e.to_string())))?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn get_stats(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneStats>, Status> {
        let handle = self.registry.get(request.into_inner().scene_id).map_err(status)?;
        Ok(Response::new(convert::scene_stats(&handle.shared)))
    }

    async fn set_parameters(
        &self,
        request: Request<pb::SetParametersRequest>,
    ) -> Result<Response<pb::SceneInfo>, Status> {
        let r = request.into_inner();
        let handle = self.registry.get(r.scene_id).map_err(status)?;
        handle.set_parameters(r.overrides).await.map_err(|e| match e {
            CommandError::BadParameter(m) => status(ServiceError::InvalidArgument(m)),
            _ => status(ServiceError::FailedPrecondition(e.to_string())),
        })?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    async fn snapshot(&self, request: Request<pb::SceneRef>) -> Result<Response<pb::SceneSnapshot>, Status> {
        let id = request.into_inner().scene_id;
        let handle = self.registry.get(id).map_err(status)?;
        let state = handle.save().await.map_err(|e| status(ServiceError::FailedPrecondition(e.to_string())))?;
        Ok(Response::new(pb::SceneSnapshot { scene_id: id, state }))
    }

    async fn restore(&self, request: Request<pb::RestoreRequest>) -> Result<Response<pb::SceneInfo>, Status> {
        let r = request.into_inner();
        let handle = self.registry.get(r.scene_id).map_err(status)?;
        handle.restore(r.state).await.map_err(|e| match e {
            CommandError::BadSnapshot(_) => status(ServiceError::InvalidArgument(e.to_string())),
            _ => status(ServiceError::FailedPrecondition(e.to_string())),
        })?;
        Ok(Response::new(convert::scene_info(&handle.shared)))
    }

    type StreamFramesStream = Streamed<pb::Frame>;

    async fn stream_frames(
        &self,
        request: Request<pb::StreamFramesRequest>,
    ) -> Result<Response<Self::StreamFramesStream>, Status> {
        let r = request.into_inner();
        let request = convert::frame_request(&r)?;
        let mut subscription = self.registry.subscribe(r.scene_id, &request).map_err(status)?;
        // Capacity 1: a frame waits for the reader only while the next one is made,
        // so a slow reader skips snapshots instead of queueing them.
        let (tx, rx) = mpsc::channel(1);
        tokio::spawn(async move {
            while let Some(frame) = subscription.next().await {
                let msg = frame
                    .map(|f| pb::Frame { data: f.data.as_ref().clone(), sequence: f.sequence, skipped: f.skipped })
                    .map_err(|e| Status::internal(e.to_string()));
                if tx.send(msg).await.is_err() {
                    break;
                }
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }

    type StreamEventsStream = Streamed<pb::SceneEvent>;

    async fn stream_events(
        &self,
        request: Request<pb::SceneRef>,
    ) -> Result<Response<Self::StreamEventsStream>, Status> {
        let id = request.into_inner().scene_id;
        let handle = self.registry.get(id).map_err(status)?;
        let mut events = handle.shared.events.subscribe();
        let (tx, rx) = mpsc::channel(16);
        tokio::spawn(async move {
            loop {
                let event = match events.recv().await {
                    Ok(e) => e,
                    Err(tokio::sync::broadcast::error::RecvError::Lagged(_)) => continue,
                    Err(tokio::sync::broadcast::error::RecvError::Closed) => break,
                };
                let last = event == Event::Deleted;
                if tx.send(Ok(convert::scene_event(id, event))).await.is_err() || last {
                    break;
                }
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}
