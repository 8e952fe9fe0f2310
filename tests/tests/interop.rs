//! What third-party clients and bad input found: reflection v1alpha, non-finite
//! numbers, malformed override paths, echoed input, undecodable requests, far
//! `until_time`, WebSocket size limits and control fields, vanished subscribers of a
//! paused scene, and error bodies of 405/414/431.

use common::{TestServer, code, http};
use floe_client::{Client, FrameRequest};
use futures_util::{SinkExt, StreamExt};
use std::time::{Duration, Instant};
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tonic::Code;

mod common;

#[tokio::test]
async fn reflection_answers_v1alpha_and_v1() {
    use tonic_reflection::pb::{v1, v1alpha};
    let server = TestServer::start().await;
    let mut alpha = v1alpha::server_reflection_client::ServerReflectionClient::new(server.channel().await);
    let request = v1alpha::ServerReflectionRequest {
        host: String::new(),
        message_request: Some(v1alpha::server_reflection_request::MessageRequest::ListServices(String::new())),
    };
    let mut answers = alpha.server_reflection_info(futures_util::stream::iter([request])).await.unwrap().into_inner();
    let Some(v1alpha::server_reflection_response::MessageResponse::ListServicesResponse(list)) =
        answers.message().await.unwrap().unwrap().message_response
    else {
        panic!("not a list of services")
    };
    let names: Vec<String> = list.service.into_iter().map(|s| s.name).collect();
    assert!(
        names.contains(&"floe.v1.SceneService".into()) && names.contains(&"floe.v1.LabService".into()),
        "{names:?}"
    );

    let mut current = v1::server_reflection_client::ServerReflectionClient::new(server.channel().await);
    let request = v1::ServerReflectionRequest {
        host: String::new(),
        message_request: Some(v1::server_reflection_request::MessageRequest::ListServices(String::new())),
    };
    let mut answers = current.server_reflection_info(futures_util::stream::iter([request])).await.unwrap().into_inner();
    assert!(answers.message().await.unwrap().unwrap().message_response.is_some());
    server.shutdown().await;
}

#[tokio::test]
async fn bad_scene_input_is_refused_naming_the_field() {
    let server = TestServer::start().await;
    let mut c = Client::connect(&server.grpc_url()).await.unwrap();
    let scene = "particle_spacing = 0.1\n[[fluids]]\nxsph = nan\nblocks = [{ min = [0, 0, 0], max = [0.5, 0.5, 0.5] }]\n\
                 [[boundaries]]\nkind = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n";
    let e = c.create_document(scene, "toml", &[]).await.unwrap_err();
    assert_eq!(e.to_string(), "fluids[0].xsph: must be a finite number, got NaN (InvalidArgument)");
    let e = c.create_document(&scene.replace("nan", "0").replace("0.1\n", "inf\n"), "toml", &[]).await.unwrap_err();
    assert_eq!(e.to_string(), "particle_spacing: must be a finite number, got inf (InvalidArgument)");

    for bad in ["particle_spacing..x=1", "fluids[+0].xsph=0.1", "fluids[0]..xsph=0.1", "fluids.[0]=1", "gravity.=1"] {
        let e = c.create_preset("dam_break", &[bad]).await.unwrap_err();
        assert_eq!(code(&e), Code::InvalidArgument, "{bad}");
        assert!(e.to_string().starts_with(&format!("override '{bad}'")), "{bad}: {e}");
    }
    server.shutdown().await;
}

#[tokio::test]
async fn huge_input_is_not_echoed_whole() {
    let server = TestServer::start().await;
    let mut c = Client::connect(&server.grpc_url()).await.unwrap();
    let huge_key = format!("{}=1", "x".repeat(1 << 20));
    let e = c.create_preset("dam_break", &[&huge_key]).await.unwrap_err();
    assert_eq!(code(&e), Code::InvalidArgument, "{e}");
    assert!(e.to_string().len() < 2048, "{} bytes", e.to_string().len());
    let e = c.create_document(&format!("name = \"{}", "y".repeat(1 << 20)), "toml", &[]).await.unwrap_err();
    assert_eq!(code(&e), Code::InvalidArgument, "{e}");
    assert!(e.to_string().len() < 2048, "{} bytes", e.to_string().len());
    let e = c.create_preset(&"z".repeat(1 << 20), &[]).await.unwrap_err();
    assert!(e.to_string().contains("bytes cut") && e.to_string().ends_with("(InvalidArgument)"), "{e}");

    let body = format!(r#"{{"preset": "dam_break", "overrides": ["{huge_key}"]}}"#);
    let a = http(server.http, "POST", "/api/v1/scenes", &[], &body).await;
    assert_eq!(a.status, 400);
    assert!(a.body.len() < 2048, "{} bytes", a.body.len());
    server.shutdown().await;
}

/// Sends raw bytes as a request: what a client with a broken encoder sends.
#[derive(Debug, Clone, Copy, Default)]
struct Raw;

impl tonic::codec::Codec for Raw {
    type Encode = Vec<u8>;
    type Decode = Vec<u8>;
    type Encoder = Raw;
    type Decoder = Raw;
    fn encoder(&mut self) -> Raw {
        Raw
    }
    fn decoder(&mut self) -> Raw {
        Raw
    }
}

impl tonic::codec::Encoder for Raw {
    type Item = Vec<u8>;
    type Error = tonic::Status;
    fn encode(&mut self, item: Vec<u8>, dst: &mut tonic::codec::EncodeBuf<'_>) -> Result<(), tonic::Status> {
        bytes::BufMut::put_slice(dst, &item);
        Ok(())
    }
}

impl tonic::codec::Decoder for Raw {
    type Item = Vec<u8>;
    type Error = tonic::Status;
    fn decode(&mut self, src: &mut tonic::codec::DecodeBuf<'_>) -> Result<Option<Vec<u8>>, tonic::Status> {
        let v = bytes::Buf::chunk(src).to_vec();
        bytes::Buf::advance(src, v.len());
        Ok(Some(v))
    }
}

#[tokio::test]
async fn an_undecodable_request_is_the_clients_error() {
    let server = TestServer::start().await;
    let mut grpc = tonic::client::Grpc::new(server.channel().await);
    // CreateSceneRequest.preset (field 1, length-delimited) holding invalid UTF-8; then a field key 0.
    for bytes in [vec![0x0a, 0x02, 0xff, 0xfe], vec![0x00, 0x01]] {
        grpc.ready().await.unwrap();
        let path = tonic::codegen::http::uri::PathAndQuery::from_static("/floe.v1.SceneService/CreateScene");
        let status = grpc.unary::<_, Vec<u8>, _>(tonic::Request::new(bytes), path, Raw).await.unwrap_err();
        assert_eq!(status.code(), Code::InvalidArgument, "{status:?}");
        assert!(status.message().starts_with("the request could not be decoded: "), "{}", status.message());
    }
    server.shutdown().await;
}

#[tokio::test]
async fn stepping_to_a_far_time_stops_when_the_caller_goes_away() {
    let server = TestServer::start().await;
    let mut c = Client::connect(&server.grpc_url()).await.unwrap();
    let id = c.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let mut stepper = c.clone();
    let gave_up = tokio::time::timeout(Duration::from_millis(300), stepper.step_until(id, 4000.0)).await;
    assert!(gave_up.is_err(), "4000 s of simulated time cannot be reached in 0.3 s");
    // Commands run in order: this step is answered only once the abandoned one ended.
    let next = tokio::time::timeout(Duration::from_secs(20), c.step(id, 1)).await;
    let info = next.expect("the abandoned stepping went on").unwrap();
    assert!(info.steps > 1 && info.sim_time < 1e3, "{info:?}");
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(c.stats(id).await.unwrap().steps, info.steps, "nothing steps the scene any more");
    server.shutdown().await;
}

#[tokio::test]
async fn websocket_limits_and_control_fields() {
    let server = TestServer::start().await;
    let mut c = Client::connect(&server.grpc_url()).await.unwrap();
    let id = c.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let url = format!("ws://{}/api/v1/scenes/{id}/ws", server.http);
    let (mut ws, _) = tokio_tungstenite::connect_async(&url).await.unwrap();
    let mut errors = Vec::new();
    for bad in [r#"{"op": "pause", "x": 1}"#, r#"{"op": "step", "steps": 1, "bogus": 2}"#, r#"{"op": "jump"}"#] {
        ws.send(Message::Text(bad.into())).await.unwrap();
        loop {
            if let Message::Text(t) = ws.next().await.unwrap().unwrap() {
                let v: serde_json::Value = serde_json::from_str(&t).unwrap();
                if v["type"] == "error" {
                    errors.push(v["message"].as_str().unwrap().to_owned());
                    break;
                }
            }
        }
    }
    assert_eq!(errors[0], "bad pause message: unknown field `x`; pause takes no fields");
    assert!(errors[1].starts_with("bad step message: unknown field `bogus`"), "{}", errors[1]);
    assert!(errors[2].starts_with("bad control message: unknown op \"jump\""), "{}", errors[2]);
    assert_eq!(c.get(id).await.unwrap().steps, 0, "no refused message stepped the scene");

    ws.send(Message::Text("x".repeat(100 << 10).into())).await.unwrap();
    let close = loop {
        match ws.next().await {
            Some(Ok(Message::Close(frame))) => break frame.expect("a close code"),
            Some(Ok(_)) => {}
            other => panic!("no close frame: {other:?}"),
        }
    };
    assert_eq!(close.code, CloseCode::Size);
    assert_eq!(close.reason.as_str(), "message too big: at most 65536 bytes");
    server.shutdown().await;
}

/// Waits until scene `id` counts `n` subscribers (at most 3 s).
async fn await_subscribers(c: &mut Client, id: u64, n: u32) {
    let t0 = Instant::now();
    while c.stats(id).await.unwrap().subscribers != n {
        assert!(
            t0.elapsed() < Duration::from_secs(3),
            "scene {id} still counts {} subscribers",
            c.stats(id).await.unwrap().subscribers
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test]
async fn vanished_subscribers_of_a_paused_scene_stop_counting() {
    let server = TestServer::start().await;
    let mut c = Client::connect(&server.grpc_url()).await.unwrap();
    let id = c.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;

    // gRPC: the client's connection goes away with its stream.
    let mut viewer = Client::connect(&server.grpc_url()).await.unwrap();
    let mut frames = viewer.frames(id, FrameRequest::default()).await.unwrap();
    frames.next().await.unwrap().unwrap();
    await_subscribers(&mut c, id, 1).await;
    drop((frames, viewer));
    await_subscribers(&mut c, id, 0).await;

    // WebSocket: an abrupt close (no close frame), then a TCP reset.
    let url = format!("ws://{}/api/v1/scenes/{id}/ws", server.http);
    for reset in [false, true] {
        let (mut ws, _) = tokio_tungstenite::connect_async(&url).await.unwrap();
        while !matches!(ws.next().await.unwrap().unwrap(), Message::Binary(_)) {}
        await_subscribers(&mut c, id, 1).await;
        if reset && let tokio_tungstenite::MaybeTlsStream::Plain(s) = ws.get_ref() {
            s.set_zero_linger().unwrap();
        }
        drop(ws);
        await_subscribers(&mut c, id, 0).await;
    }
    assert_eq!(c.get(id).await.unwrap().steps, 0, "the scene never stepped");
    server.shutdown().await;
}

#[tokio::test]
async fn http_errors_carry_the_json_body() {
    let server = TestServer::start().await;
    let a = http(server.http, "PUT", "/api/v1/presets", &[], "").await;
    assert_eq!(a.status, 405);
    assert_eq!(a.error(), "PUT is not allowed on /api/v1/presets");
    assert_eq!(a.header("allow"), Some("GET,HEAD"));
    let a = http(server.http, "POST", "/index.html", &[], "").await;
    assert_eq!(a.status, 405);
    assert_eq!(a.error(), "POST is not allowed on /index.html");

    let a = http(server.http, "GET", &format!("/api/v1/scenes?{}", "q".repeat(10 << 10)), &[], "").await;
    assert_eq!((a.status, a.error().as_str()), (414, "the URI is 10255 bytes; at most 8192 are accepted"));
    let big = "h".repeat(40 << 10);
    let a = http(server.http, "GET", "/api/v1/presets", &[("x-big", &big)], "").await;
    assert_eq!(a.status, 431);
    assert!(a.error().starts_with("the request headers are "), "{}", a.error());
    server.shutdown().await;
}
