//! The HTTP side: the REST mirror (through the router, as a request would go)
//! and the per-scene WebSocket against a real server on 127.0.0.1:0.

use axum::body::Body;
use axum::http::{Request, StatusCode};
use floe_proto::{Decoder, Limits};
use futures_util::{SinkExt, StreamExt};
use http_body_util::BodyExt;
use tokio_tungstenite::tungstenite::Message;
use tower::ServiceExt;

mod common;

async fn call(app: &axum::Router, method: &str, uri: &str, body: Option<String>) -> (StatusCode, serde_json::Value) {
    let req = Request::builder()
        .method(method)
        .uri(uri)
        .header("content-type", "application/json")
        .body(body.map(Body::from).unwrap_or_else(Body::empty))
        .unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    let status = res.status();
    let bytes = res.into_body().collect().await.unwrap().to_bytes();
    (status, serde_json::from_slice(&bytes).unwrap_or(serde_json::Value::Null))
}

#[tokio::test]
async fn rest_mirrors_the_control_calls() {
    let registry = common::cpu_registry();
    let app = floe_server::http::router(registry.clone(), "../web".into());
    let (s, v) = call(&app, "GET", "/api/v1/presets", None).await;
    assert_eq!(
        (s, v),
        (
            StatusCode::OK,
            serde_json::json!([
                "dam_break",
                "hydrostatic",
                "poiseuille",
                "taylor_green",
                "conduction",
                "convection",
                "two_fluids",
                "heated_cavity",
                "heated_channel",
                "stefan",
                "layers",
                "avalanche",
                "avalanche_thesis",
                "power_law_channel",
                "bingham_channel",
                "cross_channel",
                "snowfall",
                "snowfall_then_avalanche",
                "snow_roof",
                "elastic_drop",
                "bunny",
                "ice_melting",
                "ice_cube_in_glass",
                "floating_blocks"
            ])
        )
    );

    let body = r#"{"preset": "dam_break", "overrides": ["particle_spacing=0.05"]}"#;
    let (s, v) = call(&app, "POST", "/api/v1/scenes", Some(body.into())).await;
    assert_eq!(s, StatusCode::CREATED, "{v}");
    assert_eq!(v["particles"], 1000);
    assert_eq!(v["backend"], "cpu");
    assert_eq!(v["state"], "paused");
    assert_eq!(v["channels"][0]["name"], "velocity");
    assert_eq!(v["channels"][2]["unit"], "Pa");
    assert_eq!(v["sets"][0], serde_json::json!({"name": "particles", "count": 1000, "index": 0, "grid": false}));
    assert_eq!(
        v["materials"],
        serde_json::json!([{"name": "water", "kind": "fluid", "rest_density": 1000.0, "look": "water"}])
    );
    let id = v["scene_id"].as_u64().unwrap();

    let (s, v) = call(&app, "POST", &format!("/api/v1/scenes/{id}/step"), Some(r#"{"steps": 5}"#.into())).await;
    assert_eq!((s, v["steps"].as_u64()), (StatusCode::OK, Some(5)));
    let (s, v) = call(&app, "POST", &format!("/api/v1/scenes/{id}/step"), Some(r#"{"steps": 0}"#.into())).await;
    assert_eq!(s, StatusCode::BAD_REQUEST);
    assert!(v["error"].as_str().unwrap().starts_with("steps: must be between 1 and"), "{v}");

    let (s, v) = call(&app, "GET", "/api/v1/scenes/99", None).await;
    assert_eq!((s, v["error"].as_str()), (StatusCode::NOT_FOUND, Some("no scene with id 99")));

    let bad = r#"{"preset": "dam_break", "overrides": ["fluids[0].rest_density=-3"]}"#;
    let (s, v) = call(&app, "POST", "/api/v1/scenes", Some(bad.into())).await;
    assert_eq!(
        (s, v["error"].as_str()),
        (StatusCode::BAD_REQUEST, Some("fluids[0].rest_density: must be > 0, got -3"))
    );

    let huge = format!(r#"{{"document": "{}"}}"#, "#".repeat(9 << 20));
    let (s, _) = call(&app, "POST", "/api/v1/scenes", Some(huge)).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);

    // Snapshot and restore: the bytes come back and restore the step count.
    let req = Request::builder().uri(format!("/api/v1/scenes/{id}/snapshot")).body(Body::empty()).unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    let state = res.into_body().collect().await.unwrap().to_bytes();
    assert!(state.starts_with(b"FLOESNAP"));
    call(&app, "POST", &format!("/api/v1/scenes/{id}/step"), Some(r#"{"steps": 3}"#.into())).await;
    let req =
        Request::builder().method("PUT").uri(format!("/api/v1/scenes/{id}/snapshot")).body(Body::from(state)).unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    let (_, v) = call(&app, "GET", &format!("/api/v1/scenes/{id}"), None).await;
    assert_eq!(v["steps"], 5);
    // Measures with units, refreshed when stepping stops: the falling column has
    // picked up kinetic energy.
    let ke = &v["measures"]["fluid.kinetic_energy"];
    assert_eq!(ke["unit"], "J");
    assert!(ke["value"].as_f64().unwrap() > 0.0, "{ke}");
    assert_eq!(v["measures"]["max_speed"]["unit"], "m/s");
    let req =
        Request::builder().method("PUT").uri(format!("/api/v1/scenes/{id}/snapshot")).body(Body::from("junk")).unwrap();
    assert_eq!(app.clone().oneshot(req).await.unwrap().status(), StatusCode::BAD_REQUEST);

    let (s, v) = call(&app, "GET", "/api/v1/scenes", None).await;
    assert_eq!((s, v.as_array().map(Vec::len)), (StatusCode::OK, Some(1)));
    let (s, v) = call(&app, "DELETE", &format!("/api/v1/scenes/{id}"), None).await;
    assert_eq!((s, v["state"].as_str()), (StatusCode::OK, Some("deleted")));
    let (s, _) = call(&app, "GET", &format!("/api/v1/scenes/{id}"), None).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    registry.shutdown().await;
}

/// Bodies, ids and query parameters axum cannot parse get the API's JSON errors too.
#[tokio::test]
async fn malformed_requests_get_json_errors_naming_what_was_wrong() {
    let registry = common::cpu_registry();
    let app = floe_server::http::router(registry.clone(), "../web".into());
    let body = r#"{"preset": "dam_break", "overrides": ["particle_spacing=0.05"]}"#;
    let (_, v) = call(&app, "POST", "/api/v1/scenes", Some(body.into())).await;
    let step = format!("/api/v1/scenes/{}/step", v["scene_id"]);
    let error = |v: &serde_json::Value| v["error"].as_str().unwrap_or("(not a JSON error)").to_owned();

    let (s, v) = call(&app, "POST", &step, Some(r#"{"steps": -3}"#.into())).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(error(&v).contains("steps: invalid value: integer `-3`"), "{v}");
    let (s, v) = call(&app, "POST", &step, Some(r#"{"steps": 3"#.into())).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(error(&v).contains("EOF while parsing"), "{v}");
    let (s, v) = call(&app, "POST", "/api/v1/scenes/abc/step", Some(r#"{"steps": 3}"#.into())).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(error(&v).starts_with("scene id: "), "{v}");
    let (s, v) = call(&app, "GET", "/api/v1/scenes/1/ws?max_fps=abc", None).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert!(error(&v).contains("max_fps"), "{v}");

    let req = Request::builder().method("POST").uri(&step).body(Body::from(r#"{"steps": 3}"#)).unwrap();
    let res = app.clone().oneshot(req).await.unwrap();
    assert_eq!(res.status(), StatusCode::UNSUPPORTED_MEDIA_TYPE);
    let v: serde_json::Value = serde_json::from_slice(&res.into_body().collect().await.unwrap().to_bytes()).unwrap();
    assert!(error(&v).contains("Content-Type: application/json"), "{v}");
    registry.shutdown().await;
}

#[tokio::test]
async fn websocket_streams_frames_and_survives_garbage() {
    let mut server = common::TestServer::start().await;
    let addr = server.http;
    let preset = floe_server::service::SceneSource::Preset("dam_break".into());
    let local = floe_server::auth::Caller::local();
    let scene = server.registry.create(&local, preset, vec!["particle_spacing=0.05".into()]).await.unwrap();
    // A channel the scene lacks is refused at the handshake, naming those it has.
    let url = format!("ws://{addr}/api/v1/scenes/{}/ws?channels=velocity,temperature", scene.shared.id);
    match tokio_tungstenite::connect_async(url).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(response)) => {
            assert_eq!(response.status(), StatusCode::BAD_REQUEST);
            let body: serde_json::Value = serde_json::from_slice(&response.body().clone().unwrap_or_default()).unwrap();
            let message = body["error"].as_str().unwrap_or_default();
            assert!(
                message.ends_with("no channel \"temperature\" in set particles; it has velocity, density, pressure"),
                "{body}"
            );
        }
        other => panic!("expected a refused handshake, got {:?}", other.map(|_| ())),
    }
    let url = format!("ws://{addr}/api/v1/scenes/{}/ws?channels=velocity&max_fps=60", scene.shared.id);
    let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();

    let mut decoder = Decoder::new(Limits::default());
    let mut texts = Vec::new();
    let mut frames = 0;
    // The greeting status and a first frame.
    while frames == 0 || texts.is_empty() {
        match ws.next().await.unwrap().unwrap() {
            Message::Binary(b) => {
                let f = decoder.decode(&b).unwrap();
                assert_eq!(f.positions.len(), 1000);
                assert!(f.named("velocity").is_some());
                frames += 1;
            }
            Message::Text(t) => texts.push(serde_json::from_str::<serde_json::Value>(&t).unwrap()),
            _ => {}
        }
    }
    assert_eq!(texts[0]["type"], "status");

    // Garbage gets an error message; the connection stays usable.
    for garbage in [Message::Text("hello".into()), Message::Binary(vec![1u8, 2, 3].into())] {
        ws.send(garbage).await.unwrap();
        let reply = next_text(&mut ws).await;
        assert_eq!(reply["type"], "error", "{reply}");
    }
    ws.send(Message::Text(r#"{"op": "step", "steps": 3}"#.into())).await.unwrap();
    let reply = next_text(&mut ws).await;
    assert_eq!((reply["type"].as_str(), reply["scene"]["steps"].as_u64()), (Some("status"), Some(3)), "{reply}");
    ws.send(Message::Text(r#"{"op": "run", "real_time_factor": 0}"#.into())).await.unwrap();
    let mut more = 0;
    while more < 3 {
        if let Message::Binary(b) = ws.next().await.unwrap().unwrap() {
            decoder.decode(&b).unwrap();
            more += 1;
        }
    }
    server.stop();
    // Shutdown deletes the scene: the socket hears about it and closes.
    let mut saw_deleted = false;
    while let Some(Ok(m)) = ws.next().await {
        if let Message::Text(t) = m {
            saw_deleted |= t.contains(r#""event":"deleted""#);
        }
    }
    assert!(saw_deleted);
    server.stopped().await;
}

/// The socket's view: the query's first, then `view` messages; a bad one is an error
/// message naming the field and the socket stays open.
#[tokio::test]
async fn a_websocket_view_culls_frames_and_changes_with_a_message() {
    let mut server = common::TestServer::start().await;
    let preset = floe_server::service::SceneSource::Preset("dam_break".into());
    let local = floe_server::auth::Caller::local();
    let scene = server.registry.create(&local, preset, vec!["particle_spacing=0.05".into()]).await.unwrap();
    let id = scene.shared.id;
    let url = format!("ws://{}/api/v1/scenes/{id}/ws?mode=identity&view=%7B%22budget%22%3A25%7D", server.http);
    let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
    let mut decoder = Decoder::new(Limits::default());
    let f = decoder.decode(&next_binary(&mut ws).await).unwrap();
    assert_eq!(f.positions.len(), 25, "the query's budget");
    assert_eq!(f.ids.as_ref().map(Vec::len), Some(25));
    // A box: the column's first four layers, x <= 0.2 m.
    let text = r#"{"op": "view", "box": {"min": [-1, -1, -1], "max": [0.2, 5, 5]}}"#;
    ws.send(Message::Text(text.into())).await.unwrap();
    assert_eq!(next_text(&mut ws).await["type"], "status");
    ws.send(Message::Text(r#"{"op": "step", "steps": 1}"#.into())).await.unwrap();
    let f = loop {
        let f = decoder.decode(&next_binary(&mut ws).await).unwrap();
        if f.header.step >= 1 {
            break f;
        }
    };
    assert_eq!(f.positions.len(), 4 * 20 * 5, "four layers of the 10 x 20 x 5 column");
    assert!(f.positions.iter().all(|p| p[0] <= 0.2));
    for bad in [r#"{"op": "view", "budget": 0}"#, r#"{"op": "view", "box": {"min": [1, 1, 1]}}"#] {
        ws.send(Message::Text(bad.into())).await.unwrap();
        let reply = next_text(&mut ws).await;
        assert_eq!(reply["type"], "error", "{reply}");
        let message = reply["message"].as_str().unwrap();
        assert!(message.contains("view.budget: must be 1 to") || message.contains("missing field `max`"), "{message}");
    }
    // A bad query view is refused at the handshake.
    let url = format!("ws://{}/api/v1/scenes/{id}/ws?view=%7B%22budget%22%3A-1%7D", server.http);
    match tokio_tungstenite::connect_async(url).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(response)) => {
            assert_eq!(response.status(), StatusCode::BAD_REQUEST)
        }
        other => panic!("expected a refused handshake, got {:?}", other.map(|_| ())),
    }
    server.stop();
    server.stopped().await;
}

/// The next frame's bytes, skipping text messages.
async fn next_binary(
    ws: &mut tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>,
) -> Vec<u8> {
    loop {
        if let Message::Binary(b) = ws.next().await.unwrap().unwrap() {
            return b.to_vec();
        }
    }
}

/// The next text message, skipping frames.
async fn next_text(
    ws: &mut tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>,
) -> serde_json::Value {
    loop {
        if let Message::Text(t) = ws.next().await.unwrap().unwrap() {
            return serde_json::from_str(&t).unwrap();
        }
    }
}
