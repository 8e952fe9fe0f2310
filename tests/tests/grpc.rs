//! The gRPC service end to end: a real server on 127.0.0.1:0, a real tonic
//! client, frames decoded with floe-proto.

use floe_proto::pb::scene_service_client::SceneServiceClient;
use floe_proto::pb::{self, create_scene_request::Source};
use floe_proto::{Decoder, Limits};
use tonic::Code;
use tonic::transport::Channel;

mod common;

struct Server {
    client: SceneServiceClient<Channel>,
    server: common::TestServer,
}

async fn start() -> Server {
    let server = common::TestServer::start().await;
    Server { client: SceneServiceClient::new(server.channel().await), server }
}

impl Server {
    async fn shutdown(self) {
        self.server.shutdown().await;
    }
}

fn preset(name: &str, overrides: &[&str]) -> pb::CreateSceneRequest {
    pb::CreateSceneRequest {
        source: Some(Source::Preset(name.into())),
        document_format: String::new(),
        overrides: overrides.iter().map(|s| s.to_string()).collect(),
        backend: String::new(),
    }
}

#[tokio::test]
async fn create_step_and_stream_a_dam_break() {
    let mut s = start().await;
    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    assert_eq!(info.particles, 1000);
    assert_eq!(info.backend, "cpu");
    assert_eq!(info.state, pb::SceneState::Paused as i32);
    let id = info.scene_id;
    let stepped =
        s.client.step(pb::StepRequest { scene_id: id, steps: 20, until_time: 0.0 }).await.unwrap().into_inner();
    assert_eq!(stepped.steps, 20);
    assert!(stepped.sim_time > 0.0);

    let request = pb::StreamFramesRequest {
        scene_id: id,
        channels: vec![pb::Channel::Velocity as i32],
        max_fps: 60.0,
        position_bits: 16,
        mode: pb::FrameMode::Unordered as i32,
        decimation: 1,
        ..Default::default()
    };
    let mut frames = s.client.stream_frames(request).await.unwrap().into_inner();
    let frame = frames.message().await.unwrap().expect("a frame");
    let decoded = Decoder::new(Limits::default()).decode(&frame.data).unwrap();
    assert_eq!(decoded.positions.len(), 1000);
    assert_eq!(decoded.header.step, 20);
    assert!(decoded.named("velocity").is_some() && decoded.named("density").is_none());
    let (lo, hi) = (&info.bounds_min, &info.bounds_max);
    for p in &decoded.positions {
        for k in 0..3 {
            assert!(p[k] >= lo[k] - 1e-3 && p[k] <= hi[k] + 1e-3, "{p:?} outside {lo:?}..{hi:?}");
        }
    }

    // Identity-ordered frames of a running scene decode in sequence with one decoder.
    let request = pb::StreamFramesRequest {
        scene_id: id,
        channels: vec![],
        max_fps: 120.0,
        position_bits: 16,
        mode: pb::FrameMode::Identity as i32,
        decimation: 1,
        ..Default::default()
    };
    let mut frames = s.client.stream_frames(request).await.unwrap().into_inner();
    s.client.run(pb::RunRequest { scene_id: id, real_time_factor: 0.0 }).await.unwrap();
    let mut decoder = Decoder::new(Limits::default());
    let mut last_step = 0;
    for _ in 0..4 {
        let f = frames.message().await.unwrap().expect("a frame");
        let d = decoder.decode(&f.data).unwrap();
        assert_eq!(d.positions.len(), 1000);
        assert!(d.header.step >= last_step);
        last_step = d.header.step;
    }
    let paused = s.client.pause(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!(paused.state, pb::SceneState::Paused as i32);
    assert!(paused.steps > 20);
    let stats = s.client.get_stats(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!(stats.subscribers, 2);
    assert!(stats.frames_published >= 5);
    let ke = stats.measures.iter().find(|m| m.name == "fluid.kinetic_energy").expect("kinetic energy measured");
    assert!(ke.value > 0.0 && ke.unit == "J", "{ke:?}");

    let listed = s.client.list_scenes(pb::ListScenesRequest {}).await.unwrap().into_inner();
    assert_eq!(listed.scenes.len(), 1);
    s.client.delete_scene(pb::SceneRef { scene_id: id }).await.unwrap();
    // The frame stream ends with the scene.
    while frames.message().await.unwrap().is_some() {}
    s.shutdown().await;
}

#[tokio::test]
async fn bad_requests_get_clear_errors() {
    let mut s = start().await;
    let e = s.client.get_scene(pb::SceneRef { scene_id: 99 }).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound);
    assert_eq!(e.message(), "no scene with id 99");

    let e = s.client.create_scene(preset("dam_break", &["fluids[0].rest_density=-3"])).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert_eq!(e.message(), "fluids[0].rest_density: must be > 0, got -3");

    let doc = pb::CreateSceneRequest {
        source: Some(Source::Document("particle_spacing = \"wide\"".into())),
        document_format: "toml".into(),
        overrides: vec![],
        backend: String::new(),
    };
    let e = s.client.create_scene(doc).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("particle_spacing: invalid type"), "{}", e.message());

    // A request larger than the server accepts is refused, and the server lives on.
    let huge = pb::CreateSceneRequest {
        source: Some(Source::Document("#".repeat(9 << 20))),
        document_format: "toml".into(),
        overrides: vec![],
        backend: String::new(),
    };
    let e = s.client.create_scene(huge).await.unwrap_err();
    assert_eq!(e.code(), Code::OutOfRange, "{e:?}");

    // A backend this server does not run, or none that exists.
    let on = |backend: &str| pb::CreateSceneRequest {
        backend: backend.into(),
        ..preset("dam_break", &["particle_spacing=0.1"])
    };
    let e = s.client.create_scene(on("gpu")).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition);
    assert_eq!(e.message(), "backend: this server runs its scenes on the cpu backend, not gpu");
    let e = s.client.create_scene(on("tpu")).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert_eq!(e.message(), "backend: must be \"gpu\", \"cpu\" or empty (any), got \"tpu\"");
    assert_eq!(s.client.create_scene(on("cpu")).await.unwrap().into_inner().particles, 100);

    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    let e = s.client.step(pb::StepRequest { scene_id: info.scene_id, steps: 0, until_time: 0.0 }).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("steps: must be between 1 and"), "{}", e.message());
    s.shutdown().await;
}

#[tokio::test]
async fn an_unstable_scene_halts_with_an_event_and_the_server_lives_on() {
    let mut s = start().await;
    let info = s
        .client
        .create_scene(preset("dam_break", &["particle_spacing=0.05", "solver.speed_of_sound=0.5"]))
        .await
        .unwrap()
        .into_inner();
    let id = info.scene_id;
    let mut events = s.client.stream_events(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    let after =
        s.client.step(pb::StepRequest { scene_id: id, steps: 100_000, until_time: 0.0 }).await.unwrap().into_inner();
    assert_eq!(after.state, pb::SceneState::Halted as i32);
    assert!(after.halt_reason.contains("exceeds guard."), "{}", after.halt_reason);
    let event = events.message().await.unwrap().expect("an event");
    match event.kind {
        Some(pb::scene_event::Kind::Halted(h)) => {
            assert_eq!(format!("halted at step {}", h.step), after.halt_reason.split(',').next().unwrap())
        }
        other => panic!("expected a halt, got {other:?}"),
    }
    let e = s.client.step(pb::StepRequest { scene_id: id, steps: 1, until_time: 0.0 }).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition);
    // Reset puts the halted scene back at the start, ready to step again.
    let reset = s.client.reset(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!((reset.state, reset.steps, reset.sim_time), (pb::SceneState::Paused as i32, 0, 0.0));
    assert!(reset.halt_reason.is_empty());
    s.client.step(pb::StepRequest { scene_id: id, steps: 1, until_time: 0.0 }).await.unwrap();
    // Another scene still works.
    let other = s.client.create_scene(preset("hydrostatic", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    s.client.step(pb::StepRequest { scene_id: other.scene_id, steps: 5, until_time: 0.0 }).await.unwrap();
    s.shutdown().await;
}

#[tokio::test]
async fn shutdown_while_streaming_ends_cleanly() {
    let mut s = start().await;
    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    s.client.run(pb::RunRequest { scene_id: info.scene_id, real_time_factor: 1.0 }).await.unwrap();
    let request = pb::StreamFramesRequest { scene_id: info.scene_id, max_fps: 30.0, ..Default::default() };
    let mut frames = s.client.stream_frames(request).await.unwrap().into_inner();
    frames.message().await.unwrap().expect("a frame");
    s.shutdown().await;
    // The stream ends (cleanly or with a transport error), it does not hang.
    let end = tokio::time::timeout(std::time::Duration::from_secs(5), async {
        while let Ok(Some(_)) = frames.message().await {}
    })
    .await;
    assert!(end.is_ok(), "the frame stream did not end after shutdown");
}

#[tokio::test]
async fn snapshot_then_restore_reproduces_the_state_bit_for_bit() {
    let mut s = start().await;
    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    let id = info.scene_id;
    let step = |n| pb::StepRequest { scene_id: id, steps: n, until_time: 0.0 };
    s.client.step(step(25)).await.unwrap();
    let saved = s.client.snapshot(pb::SceneRef { scene_id: id }).await.unwrap().into_inner().state;
    s.client.step(step(15)).await.unwrap();
    let after = s.client.snapshot(pb::SceneRef { scene_id: id }).await.unwrap().into_inner().state;
    let restored =
        s.client.restore(pb::RestoreRequest { scene_id: id, state: saved.clone() }).await.unwrap().into_inner();
    assert_eq!(restored.steps, 25);
    s.client.step(step(15)).await.unwrap();
    let again = s.client.snapshot(pb::SceneRef { scene_id: id }).await.unwrap().into_inner().state;
    assert!(again == after, "the state after restoring and stepping differs");

    // A damaged snapshot, or one of another scene, is refused and the scene is unchanged.
    let e = s.client.restore(pb::RestoreRequest { scene_id: id, state: saved[..100].to_vec() }).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("state: snapshot is malformed"), "{}", e.message());
    let other = s.client.create_scene(preset("hydrostatic", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    let e = s.client.restore(pb::RestoreRequest { scene_id: other.scene_id, state: saved }).await.unwrap_err();
    assert_eq!((e.code(), e.message()), (Code::InvalidArgument, "state: the snapshot is of a different scene"));
    let unchanged = s.client.get_scene(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!(unchanged.steps, 40);
    s.shutdown().await;
}

#[tokio::test]
async fn channels_are_named_by_the_scene_and_streamed_by_name() {
    let mut s = start().await;
    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    let described: Vec<(String, u32, String, u32)> =
        info.channels.iter().map(|c| (c.name.clone(), c.tag, c.unit.clone(), c.components)).collect();
    assert_eq!(
        described,
        [
            ("velocity".into(), 1, "m/s".into(), 3),
            ("density".into(), 2, "kg/m^3".into(), 1),
            ("pressure".into(), 3, "Pa".into(), 1)
        ]
    );
    assert_eq!(info.sets.len(), 1);
    assert_eq!((info.sets[0].name.as_str(), info.sets[0].count, info.sets[0].index), ("particles", 1000, 0));
    assert!(info.tunables.iter().any(|t| t.path == "fluids[*].xsph" && t.max == Some(1.0)));
    let looks = |info: &pb::SceneInfo| -> Vec<(String, String)> {
        info.materials.iter().map(|m| (m.name.clone(), m.look.clone())).collect()
    };
    assert_eq!(looks(&info), [("water".to_string(), "water".to_string())]);
    let snow = s.client.create_scene(preset("avalanche", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    assert_eq!(looks(&snow), [("snow".to_string(), "snow".to_string())]);
    assert_eq!((snow.materials[0].kind.as_str(), snow.materials[0].rest_density), ("fluid", 300.0));

    let request = pb::StreamFramesRequest {
        scene_id: info.scene_id,
        channel_names: vec!["pressure".into(), "density".into()],
        max_fps: 60.0,
        ..Default::default()
    };
    let mut frames = s.client.stream_frames(request).await.unwrap().into_inner();
    let frame = frames.message().await.unwrap().expect("a frame");
    let decoded = Decoder::new(Limits::default()).decode(&frame.data).unwrap();
    let tags: Vec<u8> = decoded.channels.iter().map(|(k, _)| k.tag()).collect();
    assert_eq!(tags, [3, 2], "the channels asked for, in that order");
    assert_eq!(decoded.header.set, 0);

    // A channel the scene lacks is refused with the list of those it has.
    let request = pb::StreamFramesRequest {
        scene_id: info.scene_id,
        channel_names: vec!["temperature".into()],
        ..Default::default()
    };
    let e = s.client.stream_frames(request).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert_eq!(
        e.message(),
        "channels: the scene has no channel \"temperature\" in set particles; it has velocity, density, pressure"
    );
    let request =
        pb::StreamFramesRequest { scene_id: info.scene_id, particle_set: "flakes".into(), ..Default::default() };
    let e = s.client.stream_frames(request).await.unwrap_err();
    assert_eq!(e.message(), "particle_set: the scene has no set \"flakes\"; it has particles");
    s.shutdown().await;
}

/// The presets CreateScene takes, each with its line (as `floe presets`), through
/// the service and the Rust client: the engine's list, in its order.
#[tokio::test]
async fn the_presets_are_listed_with_what_they_are() {
    let mut s = start().await;
    let listed = s.client.list_presets(pb::ListPresetsRequest {}).await.unwrap().into_inner().presets;
    let names: Vec<_> = listed.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, floe_engine::scene::presets::names());
    assert!(listed.iter().all(|p| !p.about.trim().is_empty()), "{listed:?}");
    let mut client = floe_client::Client::connect(&s.server.grpc_url()).await.unwrap();
    let by_client = client.presets().await.unwrap();
    assert_eq!(by_client.len(), listed.len());
    assert_eq!(by_client[0], (listed[0].name.clone(), listed[0].about.clone()));
    s.shutdown().await;
}

/// A region of interest and a budget: the server sends the particles inside the box
/// (with their ids) or exactly the budget, the same ones each frame; WatchFrames
/// changes the view on the open stream; bad views are refused naming the field.
#[tokio::test]
async fn views_cull_and_thin_frames_and_change_on_an_open_stream() {
    let mut s = start().await;
    let info = s.client.create_scene(preset("dam_break", &["particle_spacing=0.05"])).await.unwrap().into_inner();
    let id = info.scene_id;
    let identity = |view: Option<pb::FrameView>| pb::StreamFramesRequest {
        scene_id: id,
        mode: pb::FrameMode::Identity as i32,
        view,
        ..Default::default()
    };
    let first = |mut frames: tonic::Streaming<pb::Frame>| async move {
        let f = frames.message().await.unwrap().expect("a frame");
        Decoder::new(Limits::default()).decode(&f.data).unwrap()
    };
    let all = first(s.client.stream_frames(identity(None)).await.unwrap().into_inner()).await;
    assert_eq!(all.positions.len(), 1000);
    // The box x <= 0.2 m: the column's first four layers (0.025 .. 0.175 m).
    let inside: Vec<u32> = (0..1000u32).filter(|&i| all.positions[i as usize][0] <= 0.2).collect();
    assert!(all.positions.iter().all(|p| (p[0] - 0.2).abs() > 1e-3), "no particle on the box's face");
    let boxed = pb::FrameView {
        r#box: Some(pb::ViewBox { min: vec![-1.0, -1.0, -1.0], max: vec![0.2, 5.0, 5.0] }),
        ..Default::default()
    };
    let got = first(s.client.stream_frames(identity(Some(boxed.clone()))).await.unwrap().into_inner()).await;
    assert_eq!(got.ids.as_deref(), Some(inside.as_slice()), "the particles inside, named by id");
    for (k, &i) in inside.iter().enumerate() {
        assert_eq!(got.positions[k], all.positions[i as usize]);
    }

    // WatchFrames: the box first, then a budget of 40 (the same 40 in every frame).
    let (tx, rx) = tokio::sync::mpsc::channel(4);
    let start = |r| pb::WatchFramesRequest { kind: Some(pb::watch_frames_request::Kind::Start(r)) };
    let view = |v| pb::WatchFramesRequest { kind: Some(pb::watch_frames_request::Kind::View(v)) };
    tx.send(start(identity(Some(boxed)))).await.unwrap();
    let mut frames = s.client.watch_frames(tokio_stream::wrappers::ReceiverStream::new(rx)).await.unwrap().into_inner();
    let mut decoder = Decoder::new(Limits::default());
    let f = decoder.decode(&frames.message().await.unwrap().unwrap().data).unwrap();
    assert_eq!(f.positions.len(), inside.len());
    tx.send(view(pb::FrameView { budget: 40, ..Default::default() })).await.unwrap();
    // The scene is paused: its state comes again as the new view shows it.
    let again = decoder.decode(&frames.message().await.unwrap().unwrap().data).unwrap();
    assert_eq!((again.positions.len(), again.header.step), (40, f.header.step));
    let mut kept = again.ids.unwrap();
    for _ in 0..3 {
        // Frames follow a state published after the change.
        s.client.step(pb::StepRequest { scene_id: id, steps: 1, until_time: 0.0 }).await.unwrap();
        let f = decoder.decode(&frames.message().await.unwrap().unwrap().data).unwrap();
        assert_eq!(f.positions.len(), 40);
        let ids = f.ids.unwrap();
        assert_eq!(kept, ids, "the same particles in every frame");
        kept = ids;
    }
    // A view changed while the stream waits for the paused scene's next state: the same
    // state again, at once.
    tx.send(view(pb::FrameView { budget: 20, ..Default::default() })).await.unwrap();
    let waited = tokio::time::timeout(std::time::Duration::from_secs(10), frames.message()).await;
    let f = decoder.decode(&waited.expect("a frame without a step").unwrap().unwrap().data).unwrap();
    assert_eq!(f.positions.len(), 20);
    // The same view again: the same state and particles, sent again as a frame of its own
    // (a delta on the one before, which the decoder takes).
    tx.send(view(pb::FrameView { budget: 20, ..Default::default() })).await.unwrap();
    let same = decoder.decode(&frames.message().await.unwrap().unwrap().data).unwrap();
    assert_eq!((&same.ids, same.header.step, same.positions.clone()), (&f.ids, f.header.step, f.positions.clone()));
    assert!(same.header.sequence > f.header.sequence && !same.header.keyframe);
    // A bad view ends the stream with the field named.
    let bad = pb::FrameView {
        camera: Some(pb::ViewCamera { position: vec![0.0; 3], direction: vec![0.0; 3], ..Default::default() }),
        ..Default::default()
    };
    tx.send(view(bad)).await.unwrap();
    s.client.step(pb::StepRequest { scene_id: id, steps: 1, until_time: 0.0 }).await.unwrap();
    let e = loop {
        match frames.message().await {
            Ok(Some(_)) => continue,
            Ok(None) => panic!("the stream ended without the reason"),
            Err(e) => break e,
        }
    };
    assert_eq!((e.code(), e.message()), (Code::InvalidArgument, "view.camera.direction: must not be zero"));

    // A first request that is not a start, a view with decimation, a view of two values.
    let (tx, rx) = tokio::sync::mpsc::channel(1);
    tx.send(view(pb::FrameView::default())).await.unwrap();
    let e = s.client.watch_frames(tokio_stream::wrappers::ReceiverStream::new(rx)).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("start:"), "{}", e.message());
    let decimated =
        pb::StreamFramesRequest { decimation: 2, ..identity(Some(pb::FrameView { budget: 10, ..Default::default() })) };
    let e = s.client.stream_frames(decimated).await.unwrap_err();
    assert_eq!(e.message(), "view: a region or budget replaces decimation; ask for decimation 1, got 2");
    let short = pb::FrameView {
        r#box: Some(pb::ViewBox { min: vec![0.0, 0.0], max: vec![1.0, 1.0, 1.0] }),
        ..Default::default()
    };
    let e = s.client.stream_frames(identity(Some(short))).await.unwrap_err();
    assert_eq!((e.code(), e.message()), (Code::InvalidArgument, "view.box.min: must have 3 values, got 2"));
    s.shutdown().await;
}
