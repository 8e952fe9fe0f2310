//! Where generated protobuf types meet the service API: conversions both ways
//! and the mapping of service errors to gRPC codes.

use crate::service::ServiceError;
use crate::service::frames::FrameOptions;
use crate::service::{Event, Shared, State};
use floe_engine::Channel;
use floe_engine::scene::load::Format;
use floe_proto::Mode;
use floe_proto::pb;
use std::sync::atomic::Ordering;
use tonic::{Code, Status};

/// The gRPC status of a service error, its message bounded ([`crate::echo`]).
pub fn status(e: ServiceError) -> Status {
    let code = match e {
        ServiceError::NotFound(_) | ServiceError::Missing(_) => Code::NotFound,
        ServiceError::InvalidArgument(_) => Code::InvalidArgument,
        ServiceError::FailedPrecondition(_) => Code::FailedPrecondition,
        ServiceError::ResourceExhausted(_) => Code::ResourceExhausted,
        ServiceError::PermissionDenied(_) => Code::PermissionDenied,
        ServiceError::Unavailable(_) => Code::Unavailable,
        ServiceError::Unauthenticated(_) => Code::Unauthenticated,
    };
    Status::new(code, crate::echo::bounded(&e.to_string()))
}

/// `document_format` of a create request.
pub fn document_format(name: &str) -> Result<Format, Status> {
    match name {
        "" | "toml" => Ok(Format::Toml),
        "json" => Ok(Format::Json),
        other => Err(Status::invalid_argument(format!(
            "document_format: must be \"toml\" or \"json\", got {:?}",
            crate::echo::cap(other)
        ))),
    }
}

fn state(s: State) -> pb::SceneState {
    match s {
        State::Paused => pb::SceneState::Paused,
        State::Running => pb::SceneState::Running,
        State::Halted => pb::SceneState::Halted,
        State::Deleted => pb::SceneState::Deleted,
    }
}

/// The `SceneInfo` of a scene.
pub fn scene_info(shared: &Shared) -> pb::SceneInfo {
    let s = shared.status();
    pb::SceneInfo {
        scene_id: shared.id,
        name: shared.name.clone(),
        state: state(s.state) as i32,
        sim_time: s.time,
        steps: s.steps,
        particles: shared.particles as u64,
        bounds_min: shared.bounds.0.to_vec(),
        bounds_max: shared.bounds.1.to_vec(),
        halt_reason: s.halt_reason.unwrap_or_default(),
        scene_json: shared.scene_json(),
        backend: shared.backend.to_string(),
        owner: shared.owner.clone(),
    }
}

/// The `SceneStats` of a scene.
pub fn scene_stats(shared: &Shared) -> pb::SceneStats {
    let s = shared.status();
    pb::SceneStats {
        scene_id: shared.id,
        state: state(s.state) as i32,
        sim_time: s.time,
        steps: s.steps,
        particles: shared.particles as u64,
        steps_per_second: s.steps_per_second,
        dt: s.dt,
        subscribers: shared.subscribers.load(Ordering::Relaxed),
        dropped_frames: shared.dropped_frames(),
        frames_published: shared.published.load(Ordering::Relaxed),
        name: shared.name.clone(),
        owner: shared.owner.clone(),
        frame_bytes: shared.frame_bytes.load(Ordering::Relaxed),
    }
}

/// Frame options of a stream request, checked.
pub fn frame_options(r: &pb::StreamFramesRequest) -> Result<FrameOptions, Status> {
    let mut channels = Vec::new();
    for (i, &c) in r.channels.iter().enumerate() {
        let c = match pb::Channel::try_from(c) {
            Ok(pb::Channel::Velocity) => Channel::Velocity,
            Ok(pb::Channel::Density) => Channel::Density,
            Ok(pb::Channel::Pressure) => Channel::Pressure,
            _ => return Err(Status::invalid_argument(format!("channels[{i}]: unknown channel {c}"))),
        };
        if !channels.contains(&c) {
            channels.push(c);
        }
    }
    let max_fps = if r.max_fps == 0.0 { 30.0 } else { r.max_fps };
    if !(max_fps.is_finite() && max_fps > 0.0 && max_fps <= 240.0) {
        return Err(Status::invalid_argument(format!("max_fps: must be between 0 and 240, got {}", r.max_fps)));
    }
    let position_bits = if r.position_bits == 0 { 16 } else { r.position_bits };
    if !(8..=16).contains(&position_bits) {
        return Err(Status::invalid_argument(format!("position_bits: must be 8 to 16, got {}", r.position_bits)));
    }
    let mode = match pb::FrameMode::try_from(r.mode) {
        Ok(pb::FrameMode::Unordered) => Mode::Unordered,
        Ok(pb::FrameMode::Identity) => Mode::IdentityOrdered,
        Err(_) => return Err(Status::invalid_argument(format!("mode: unknown frame mode {}", r.mode))),
    };
    if r.decimation > 1000 {
        return Err(Status::invalid_argument(format!("decimation: must be 0 to 1000, got {}", r.decimation)));
    }
    Ok(FrameOptions { channels, max_fps, position_bits: position_bits as u8, mode, decimation: r.decimation.max(1) })
}

/// A scene event as a message.
pub fn scene_event(scene_id: u64, e: Event) -> pb::SceneEvent {
    let kind = match e {
        Event::Halted(h) => pb::scene_event::Kind::Halted(pb::Halted {
            step: h.step,
            sim_time: h.time,
            reason: h.reason,
            particle: h.particle,
        }),
        Event::ParameterChanged(overrides) => {
            pb::scene_event::Kind::ParameterChanged(pb::ParameterChanged { overrides })
        }
        Event::Deleted => pb::scene_event::Kind::Deleted(pb::Deleted {}),
    };
    pb::SceneEvent { scene_id, kind: Some(kind) }
}
