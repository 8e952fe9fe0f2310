//! Where generated protobuf types meet the service API: conversions both ways
//! and the mapping of service errors to gRPC codes.

use crate::service::ServiceError;
use crate::service::options::FrameRequest;
use crate::service::view::{BoxRequest, CameraRequest, ViewRequest};
use crate::service::{Event, Shared, State};
use floe_engine::scene::load::Format;
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
        ServiceError::Elsewhere { ref worker, .. } => {
            // UNAVAILABLE: retry, naming the worker in the `floe-worker` header.
            let mut status = Status::unavailable(crate::echo::bounded(&e.to_string()));
            if let Ok(value) = worker.parse() {
                status.metadata_mut().insert(crate::cluster::WORKER_HEADER, value);
            }
            return status;
        }
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
pub fn scene_info(shared: &Shared, worker: &str) -> pb::SceneInfo {
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
        channels: shared
            .channels
            .iter()
            .map(|c| pb::ChannelDescription {
                name: c.spec.name.into(),
                tag: c.kind.tag().into(),
                unit: c.spec.unit.into(),
                components: c.spec.components.into(),
                set: c.spec.set.into(),
                exact: c.spec.exact,
                about: c.spec.about.into(),
                module: c.spec.module.into(),
            })
            .collect(),
        sets: sets(shared),
        tunables: shared
            .tunables
            .iter()
            .map(|t| pb::Tunable {
                path: t.path.into(),
                unit: t.unit.into(),
                min: t.min,
                max: t.max,
                about: t.about.into(),
                module: t.module.into(),
            })
            .collect(),
        materials: shared
            .materials
            .iter()
            .map(|m| pb::MaterialDescription {
                name: m.name.clone(),
                kind: m.kind.name().into(),
                rest_density: m.rest_density,
                look: m.look.name().into(),
            })
            .collect(),
        owner: shared.owner.clone(),
        worker: worker.to_owned(),
        sizing: shared.sizing().map(|s| pb::Sizing {
            spacing: s.spacing,
            particles: s.particles as u64,
            real_time_factor: s.rtf,
            full_spacing: s.full_spacing,
            full_particles: s.full_particles,
        }),
    }
}

fn sets(shared: &Shared) -> Vec<pb::ParticleSet> {
    let set = |(i, s): (usize, &crate::service::shared::SceneSet)| pb::ParticleSet {
        name: s.name.into(),
        count: s.count as u64,
        index: i as u32,
        grid: s.grid,
        look: s.look.unwrap_or_default().into(),
        surface: s.surface.unwrap_or_default().into(),
        shade: s.shade.unwrap_or_default().into(),
        part_of: s.part_of.unwrap_or_default().into(),
    };
    shared.sets.iter().enumerate().map(set).collect()
}

/// The `SceneStats` of a scene this worker (`worker`, empty on a single server) holds.
pub fn scene_stats(shared: &Shared, worker: &str) -> pb::SceneStats {
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
        sets: sets(shared),
        measures: s
            .measures
            .iter()
            .map(|m| pb::Measure { name: m.name.clone(), value: m.value, unit: m.unit.clone() })
            .collect(),
        name: shared.name.clone(),
        owner: shared.owner.clone(),
        frame_bytes: shared.frame_bytes.load(Ordering::Relaxed),
        worker: worker.to_string(),
    }
}

/// The frame options a stream request states (checked against the scene by the service).
pub fn frame_request(r: &pb::StreamFramesRequest) -> Result<FrameRequest, Status> {
    let mut channels = Vec::new();
    for (i, &c) in r.channels.iter().enumerate() {
        let name = match pb::Channel::try_from(c) {
            Ok(pb::Channel::Velocity) => "velocity",
            Ok(pb::Channel::Density) => "density",
            Ok(pb::Channel::Pressure) => "pressure",
            _ => return Err(Status::invalid_argument(format!("channels[{i}]: unknown channel {c}"))),
        };
        channels.push(name.to_string());
    }
    channels.extend(r.channel_names.iter().cloned());
    let mode = match pb::FrameMode::try_from(r.mode) {
        Ok(pb::FrameMode::Unordered) => "unordered",
        Ok(pb::FrameMode::Identity) => "identity",
        Err(_) => return Err(Status::invalid_argument(format!("mode: unknown frame mode {}", r.mode))),
    };
    let set = |s: u32| (s != 0).then_some(s);
    Ok(FrameRequest {
        channels,
        max_fps: (r.max_fps != 0.0).then_some(r.max_fps),
        position_bits: set(r.position_bits),
        mode: Some(mode.into()),
        decimation: set(r.decimation),
        set: Some(r.particle_set.clone()),
        view: r.view.as_ref().map(view_request).transpose()?.unwrap_or_default(),
    })
}

/// The view a `FrameView` states (checked by the service); a vector of the wrong
/// length is refused naming the field.
pub fn view_request(v: &pb::FrameView) -> Result<ViewRequest, Status> {
    let three = |name: &str, x: &[f64]| -> Result<[f64; 3], Status> {
        <[f64; 3]>::try_from(x)
            .map_err(|_| Status::invalid_argument(format!("{name}: must have 3 values, got {}", x.len())))
    };
    let bounds = match &v.r#box {
        None => None,
        Some(b) => Some(BoxRequest { min: three("view.box.min", &b.min)?, max: three("view.box.max", &b.max)? }),
    };
    let camera = match &v.camera {
        None => None,
        Some(c) => Some(CameraRequest {
            position: three("view.camera.position", &c.position)?,
            direction: three("view.camera.direction", &c.direction)?,
            fov_deg: (c.fov_deg != 0.0).then_some(c.fov_deg),
            far: (c.far != 0.0).then_some(c.far),
        }),
    };
    Ok(ViewRequest { bounds, camera, budget: (v.budget != 0).then_some(v.budget) })
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
        Event::StepAbandoned { left_at, stopped_at } => pb::scene_event::Kind::StepAbandoned(pb::StepAbandoned {
            left_at_step: left_at,
            stopped_at_step: stopped_at,
        }),
        Event::Deleted => pb::scene_event::Kind::Deleted(pb::Deleted {}),
    };
    pb::SceneEvent { scene_id, kind: Some(kind) }
}

/// A scene state as the database records it.
fn recorded_state(state: &str) -> pb::SceneState {
    match state {
        "running" => pb::SceneState::Running,
        "halted" => pb::SceneState::Halted,
        _ => pb::SceneState::Paused,
    }
}

/// The `SceneInfo` of a scene held by another worker of the cluster: what the
/// database records of it.
pub fn placed_info(p: &crate::service::Placed) -> pb::SceneInfo {
    pb::SceneInfo {
        scene_id: p.id,
        name: p.name.clone(),
        state: recorded_state(&p.state) as i32,
        particles: p.particles,
        owner: p.owner.clone(),
        worker: p.worker.clone(),
        ..Default::default()
    }
}

/// The `SceneStats` of a scene held by another worker of the cluster: its figures
/// as that worker published them with its last heartbeat (zero before the first).
pub fn placed_stats(p: &crate::service::Placed) -> pb::SceneStats {
    let live = p.live.clone().unwrap_or_default();
    pb::SceneStats {
        scene_id: p.id,
        state: recorded_state(&p.state) as i32,
        sim_time: live.sim_time,
        steps: live.steps,
        particles: p.particles,
        steps_per_second: live.steps_per_second,
        subscribers: u32::try_from(live.subscribers).unwrap_or(u32::MAX),
        dropped_frames: live.dropped_frames,
        frames_published: live.frames_published,
        name: p.name.clone(),
        owner: p.owner.clone(),
        frame_bytes: live.frame_bytes,
        worker: p.worker.clone(),
        ..Default::default()
    }
}
