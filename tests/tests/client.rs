//! The Rust client against a real server: create, step, frames as position
//! arrays, a recording written and replayed, snapshots, errors.

use floe_client::recording::{self, Recorder};
use floe_client::{Client, ClientError, FrameRequest};

mod common;

#[tokio::test]
async fn the_client_drives_a_scene_and_records_it() {
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let scene = floe.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap();
    let id = scene.scene_id;
    assert_eq!(floe.step(id, 10).await.unwrap().steps, 10);
    let t = floe.step_until(id, 0.02).await.unwrap().sim_time;
    assert!(t >= 0.02);

    let mut frames = floe.frames(id, FrameRequest::default()).await.unwrap();
    let first = frames.next().await.unwrap().expect("a frame");
    assert_eq!(first.positions.len(), 1000);
    let request = FrameRequest { decimation: 10, ..FrameRequest::default() };
    let mut tenth = floe.frames(id, request).await.unwrap();
    let decimated = tenth.next().await.unwrap().expect("a frame");
    assert_eq!(decimated.positions.len(), 100);
    assert_eq!(decimated.positions[3], first.positions[30]);
    drop(tenth);
    // A watched stream: a budget of 50 first, then the whole scene again.
    let budget = floe_proto::pb::FrameView { budget: 50, ..Default::default() };
    let request = FrameRequest { view: Some(budget), ..FrameRequest::default() };
    let mut watched = floe.watch_frames(id, request).await.unwrap();
    assert_eq!(watched.next().await.unwrap().expect("a frame").positions.len(), 50);
    watched.set_view(None).await.unwrap();
    floe.step(id, 1).await.unwrap();
    assert_eq!(watched.next().await.unwrap().expect("a frame").positions.len(), 1000);
    assert!(frames.set_view(None).await.is_err(), "a StreamFrames stream's view is fixed");
    drop(watched);
    drop(frames);
    // A recording starts on a fresh stream, whose first frame is a keyframe.
    let mut frames = floe.frames(id, FrameRequest::default()).await.unwrap();
    floe.run(id, 0.0).await.unwrap();
    let mut rec = Recorder::new(Vec::new()).unwrap();
    for _ in 0..5 {
        rec.push(&frames.next_raw().await.unwrap().expect("a frame")).unwrap();
    }
    floe.pause(id).await.unwrap();
    let bytes = rec.finish().unwrap();
    let replayed = recording::read(bytes.as_slice()).unwrap();
    assert_eq!(replayed.len(), 5);
    assert!(replayed.iter().all(|f| f.positions.len() == 1000));
    assert!(replayed.windows(2).all(|w| w[0].header.step <= w[1].header.step));
    assert!(recording::read(&b"NOTAREC!"[..]).is_err());

    let state = floe.snapshot(id).await.unwrap();
    let steps = floe.get(id).await.unwrap().steps;
    floe.step(id, 3).await.unwrap();
    assert_eq!(floe.restore(id, state).await.unwrap().steps, steps);

    let mut events = floe.events(id).await.unwrap();
    floe.set_parameters(id, &["gravity=[0,-1.62,0]"]).await.unwrap();
    let event = events.message().await.unwrap().expect("an event");
    match event.kind {
        Some(floe_proto::pb::scene_event::Kind::ParameterChanged(p)) => {
            assert_eq!(p.overrides, ["gravity=[0,-1.62,0]"])
        }
        other => panic!("expected a parameter change, got {other:?}"),
    }
    match floe.set_parameters(id, &["particle_spacing=0.01"]).await {
        Err(ClientError::Status(s)) => {
            assert_eq!(s.code(), tonic::Code::InvalidArgument);
            assert!(
                s.message().starts_with("particle_spacing: cannot change while the scene exists"),
                "{}",
                s.message()
            );
        }
        other => panic!("expected InvalidArgument, got {other:?}"),
    }

    match floe.get(404).await {
        Err(ClientError::Status(s)) => assert_eq!(s.code(), tonic::Code::NotFound),
        other => panic!("expected NotFound, got {other:?}"),
    }
    assert_eq!(floe.list().await.unwrap().len(), 1);
    floe.delete(id).await.unwrap();
    server.shutdown().await;
}
