//! Stepping and steering a scene as a careless script would, over gRPC and REST:
//! a step to a time too far ahead is refused naming the limit, a step whose caller
//! leaves (a cancelled call, a closed connection or socket) stops within one step of
//! the server learning it and says so on the scene's events, a refused change of
//! several settings names only the keys refused and applies nothing, and a scene
//! file without fluids is told so.

use floe_proto::pb::scene_service_client::SceneServiceClient;
use floe_proto::pb::{self, create_scene_request::Source};
use futures_util::{SinkExt, StreamExt};
use std::time::Duration;
use tokio::io::AsyncWriteExt;
use tokio_tungstenite::tungstenite::Message;
use tonic::Code;
use tonic::transport::Channel;

mod common;

fn preset(name: &str, overrides: &[&str]) -> pb::CreateSceneRequest {
    pb::CreateSceneRequest {
        source: Some(Source::Preset(name.into())),
        document_format: String::new(),
        overrides: overrides.iter().map(|s| s.to_string()).collect(),
        backend: String::new(),
    }
}

async fn steps(client: &mut SceneServiceClient<Channel>, id: u64) -> u64 {
    client.get_scene(pb::SceneRef { scene_id: id }).await.unwrap().into_inner().steps
}

#[tokio::test]
async fn a_step_to_a_time_too_far_ahead_is_refused_naming_the_limit() {
    let server = common::TestServer::start().await;
    let mut client = SceneServiceClient::new(server.channel().await);
    let id =
        client.create_scene(preset("hydrostatic", &["particle_spacing=0.05"])).await.unwrap().into_inner().scene_id;
    let e = client.step(pb::StepRequest { scene_id: id, steps: 0, until_time: 1e12 }).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    // The adaptive control's largest step is 5 ms: 1e6 of them reach 5000 s.
    assert!(
        e.message().starts_with("until_time: 1000000000000 s is more than 1000000 steps ahead of t = 0 s")
            && e.message().contains("(steps are at most 0.005 s)")
            && e.message().contains("ask for at most 4999.99 s"),
        "{}",
        e.message()
    );
    let answer =
        common::http(server.http, "POST", &format!("/api/v1/scenes/{id}/step"), &[], r#"{"until_time": 1e12}"#).await;
    assert_eq!(answer.status, 400, "{}", answer.error());
    assert!(answer.error().contains("more than 1000000 steps ahead"), "{}", answer.error());
    assert_eq!(steps(&mut client, id).await, 0, "nothing was stepped");
    // A time within reach steps there.
    let info = client.step(pb::StepRequest { scene_id: id, steps: 0, until_time: 0.01 }).await.unwrap().into_inner();
    assert!(info.sim_time >= 0.01 && info.state == pb::SceneState::Paused as i32, "{info:?}");
    server.shutdown().await;
}

/// Waits (10 s at most) for the scene's next `StepAbandoned` event and checks that
/// the scene stopped within one step of the server learning the caller had left,
/// and stays there. Returns the step it stopped at.
async fn stopped_within_one_step(
    client: &mut SceneServiceClient<Channel>,
    events: &mut tonic::Streaming<pb::SceneEvent>,
    id: u64,
    how: &str,
) -> u64 {
    let abandoned = loop {
        let event = tokio::time::timeout(Duration::from_secs(10), events.message())
            .await
            .unwrap_or_else(|_| panic!("{how}: no StepAbandoned event 10 s after the caller left"))
            .unwrap()
            .expect("the event stream ended");
        if let Some(pb::scene_event::Kind::StepAbandoned(a)) = event.kind {
            break a;
        }
    };
    let (left, stopped) = (abandoned.left_at_step, abandoned.stopped_at_step);
    assert!(left > 0, "{how}: it stepped before the caller left");
    assert!(stopped <= left + 1, "{how}: the caller left at step {left}, the scene stopped at step {stopped}");
    // Nothing steps on afterwards.
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(steps(client, id).await, stopped, "{how}: stepped on after it stopped");
    stopped
}

#[tokio::test(flavor = "multi_thread")]
async fn stepping_stops_within_one_step_when_the_caller_leaves() {
    let server = common::TestServer::start().await;
    let mut client = SceneServiceClient::new(server.channel().await);
    // About 8,000 particles: a step takes some milliseconds, so "within one step" is
    // a count that can be checked.
    let id = client.create_scene(preset("dam_break", &["particle_spacing=0.025"])).await.unwrap().into_inner().scene_id;
    let mut events = client.stream_events(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();

    // gRPC: a deadline of half a second on a step to t = 1000 s.
    let mut request = tonic::Request::new(pb::StepRequest { scene_id: id, steps: 0, until_time: 1000.0 });
    request.set_timeout(Duration::from_millis(500));
    let e = client.step(request).await.unwrap_err();
    // The client's deadline or the server's (which tonic reports as cancelled), whichever fires first.
    assert!(matches!(e.code(), Code::DeadlineExceeded | Code::Cancelled), "{e:?}");
    let stopped = stopped_within_one_step(&mut client, &mut events, id, "gRPC deadline").await;
    let info = client.get_scene(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!(info.state, pb::SceneState::Paused as i32);

    // REST: the connection closed half a second into a step to t = 1000 s.
    let mut tcp = tokio::net::TcpStream::connect(server.http).await.unwrap();
    let body = r#"{"until_time": 1000}"#;
    let head = format!(
        "POST /api/v1/scenes/{id}/step HTTP/1.1\r\nhost: localhost\r\ncontent-type: application/json\r\n\
         content-length: {}\r\n\r\n{body}",
        body.len()
    );
    tcp.write_all(head.as_bytes()).await.unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    drop(tcp);
    let stopped_again = stopped_within_one_step(&mut client, &mut events, id, "REST connection closed").await;
    assert!(stopped_again > stopped, "it stepped while the connection was open");

    // WebSocket: a step sent as a control message, frames flowing meanwhile; the
    // socket dropped half a second in.
    let url = format!("ws://{}/api/v1/scenes/{id}/ws?channels=velocity&max_fps=30", server.http);
    let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
    ws.send(Message::Text(r#"{"op": "step", "until_time": 1000}"#.into())).await.unwrap();
    let (mut frames, t0) = (0, std::time::Instant::now());
    while t0.elapsed() < Duration::from_millis(500) {
        if let Ok(Some(Ok(Message::Binary(_)))) = tokio::time::timeout(Duration::from_millis(100), ws.next()).await {
            frames += 1;
        }
    }
    drop(ws);
    let stopped_ws = stopped_within_one_step(&mut client, &mut events, id, "WebSocket dropped").await;
    assert!(stopped_ws > stopped_again, "it stepped while the socket was open");
    assert!(frames >= 2, "frames kept flowing during the step: {frames}");

    // The scene is consistent at a step boundary: it steps on as asked.
    let info = client.step(pb::StepRequest { scene_id: id, steps: 2, until_time: 0.0 }).await.unwrap().into_inner();
    assert_eq!(info.steps, stopped_ws + 2);
    server.shutdown().await;
}

#[tokio::test]
async fn a_refused_change_names_only_the_refused_keys_and_applies_nothing() {
    let server = common::TestServer::start().await;
    let mut client = SceneServiceClient::new(server.channel().await);
    let info = client.create_scene(preset("dam_break", &["particle_spacing=0.1"])).await.unwrap().into_inner();
    let id = info.scene_id;
    let overrides = vec!["fluids[0].xsph=0.1".to_string(), "particle_spacing=0.02".to_string()];
    let e = client.set_parameters(pb::SetParametersRequest { scene_id: id, overrides }).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    let lines: Vec<&str> = e.message().lines().collect();
    assert_eq!(lines[0], "particle_spacing: cannot change while the scene exists", "{}", e.message());
    assert!(lines[1].starts_with("nothing was applied; tunable fields are "), "{}", e.message());
    assert!(!e.message().contains("fluids[0].xsph:"), "{}", e.message());

    let body = r#"{"overrides": ["gravity=[0,-1,0]", "fluids[0].xsph=3", "solver.kernel=\"mueller\""]}"#;
    let answer = common::http(server.http, "POST", &format!("/api/v1/scenes/{id}/parameters"), &[], body).await;
    assert_eq!(answer.status, 400, "{}", answer.error());
    let message = answer.error();
    assert_eq!(
        message.lines().collect::<Vec<_>>()[..2],
        ["fluids[0].xsph: must be between 0 and 1, got 3", "solver.kernel: cannot change while the scene exists"],
        "{message}"
    );
    assert!(!message.contains("gravity:"), "{message}");

    // All or nothing: neither call changed the scene, not even its fine keys.
    let after = client.get_scene(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    assert_eq!(after.scene_json, info.scene_json);
    // The fine keys alone are applied.
    let overrides = vec!["fluids[0].xsph=0.1".to_string(), "gravity=[0,-1,0]".to_string()];
    client.set_parameters(pb::SetParametersRequest { scene_id: id, overrides }).await.unwrap();
    server.shutdown().await;
}

#[tokio::test]
async fn a_scene_without_fluids_is_told_what_its_file_lacks() {
    let server = common::TestServer::start().await;
    let mut client = SceneServiceClient::new(server.channel().await);
    let document = "particle_spacing = 0.05\n".to_string();
    let request = pb::CreateSceneRequest {
        source: Some(Source::Document(document)),
        document_format: "toml".into(),
        overrides: vec![],
        backend: String::new(),
    };
    let e = client.create_scene(request).await.unwrap_err();
    assert_eq!((e.code(), e.message()), (Code::InvalidArgument, "fluids: at least one fluid is required"));
    let body = r#"{"document": "{\"particle_spacing\": 0.05}", "document_format": "json"}"#;
    let answer = common::http(server.http, "POST", "/api/v1/scenes", &[], body).await;
    assert_eq!((answer.status, answer.error().as_str()), (400, "fluids: at least one fluid is required"));
    server.shutdown().await;
}
