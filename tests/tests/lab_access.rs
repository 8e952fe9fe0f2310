//! A lab server's users cannot list, read, step, stream, snapshot or delete each
//! other's scenes, over gRPC, REST or WebSocket; a share link watches but does not
//! steer; admin-only calls and a missing or bad token get their own codes; a token
//! revoked with `floe admin` stops working on the running server.

use common::{Lab, code, http, ws_request};
use floe_client::{Client, FrameRequest};
use floe_server::service::Options;
use futures_util::{SinkExt, StreamExt};
use tokio_tungstenite::tungstenite::{Error as WsError, Message};
use tonic::Code;

mod common;

/// Every gRPC call on scene `id` that another user must not get through, with the code
/// it got.
async fn grpc_calls(c: &mut Client, id: u64) -> Vec<(&'static str, Code)> {
    let mut got = Vec::new();
    macro_rules! call {
        ($name:literal, $e:expr) => {
            got.push(($name, $e.await.map(|_| ()).map_err(|e| code(&e)).err().unwrap_or(Code::Ok)))
        };
    }
    call!("get", c.get(id));
    call!("stats", c.stats(id));
    call!("step", c.step(id, 1));
    call!("run", c.run(id, 1.0));
    call!("pause", c.pause(id));
    call!("reset", c.reset(id));
    call!("set", c.set_parameters(id, &["gravity=[0,-1,0]"]));
    call!("snapshot", c.snapshot(id));
    call!("restore", c.restore(id, b"FLOESNAP".to_vec()));
    call!("checkpoint", c.checkpoint(id));
    call!("share", c.share(id));
    call!("frames", c.frames(id, FrameRequest::default()));
    call!("events", c.events(id));
    call!("delete", c.delete(id));
    got
}

#[tokio::test]
async fn users_see_and_touch_only_their_own_scenes() {
    let lab = Lab::start(&[("alice", false), ("bob", false), ("root", true)], Options::default()).await;
    let (mut alice, mut bob, mut root) = (lab.client("alice").await, lab.client("bob").await, lab.client("root").await);
    let scene = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap();
    let id = scene.scene_id;
    assert_eq!(scene.owner, "alice");

    // gRPC: bob cannot list it, and every call on it is NOT_FOUND, as for a scene that
    // does not exist (its existence does not leak).
    assert!(bob.list().await.unwrap().is_empty());
    assert!(bob.all_stats().await.unwrap().is_empty());
    for (name, c) in grpc_calls(&mut bob, id).await {
        assert_eq!(c, Code::NotFound, "bob's {name} on alice's scene");
    }
    let missing = bob.get(id).await.unwrap_err().to_string();
    assert_eq!(missing, format!("no scene with id {id} (NotFound)"));
    assert_eq!(bob.get(9999).await.unwrap_err().to_string(), "no scene with id 9999 (NotFound)");

    // REST: the same, 404 with the same message.
    let bearer = format!("Bearer {}", lab.token("bob"));
    let auth = [("authorization", bearer.as_str())];
    for (method, path, body) in [
        ("GET", format!("/api/v1/scenes/{id}"), ""),
        ("GET", format!("/api/v1/scenes/{id}/stats"), ""),
        ("GET", format!("/api/v1/scenes/{id}/terrain"), ""),
        ("POST", format!("/api/v1/scenes/{id}/step"), r#"{"steps": 1}"#),
        ("POST", format!("/api/v1/scenes/{id}/run"), r#"{"real_time_factor": 1}"#),
        ("POST", format!("/api/v1/scenes/{id}/pause"), ""),
        ("POST", format!("/api/v1/scenes/{id}/parameters"), r#"{"overrides": ["gravity=[0,-1,0]"]}"#),
        ("GET", format!("/api/v1/scenes/{id}/snapshot"), ""),
        ("POST", format!("/api/v1/scenes/{id}/checkpoint"), ""),
        ("POST", format!("/api/v1/scenes/{id}/shares"), ""),
        ("DELETE", format!("/api/v1/scenes/{id}"), ""),
    ] {
        let a = http(lab.server.http, method, &path, &auth, body).await;
        assert_eq!((a.status, a.error()), (404, format!("no scene with id {id}")), "bob's {method} {path}");
    }
    let a = http(lab.server.http, "GET", "/api/v1/scenes", &auth, "").await;
    assert_eq!((a.status, a.json()), (200, serde_json::json!([])));

    // WebSocket: refused at the handshake.
    let url = format!("ws://{}/api/v1/scenes/{id}/ws", lab.server.http);
    match tokio_tungstenite::connect_async(ws_request(&url, Some(lab.token("bob")))).await {
        Err(WsError::Http(r)) => assert_eq!(r.status(), 404),
        other => panic!("bob's WebSocket on alice's scene: {:?}", other.map(|_| ())),
    }
    let (mut ws, _) = tokio_tungstenite::connect_async(ws_request(&url, Some(lab.token("alice")))).await.unwrap();
    ws.close(None).await.unwrap();

    // The admin sees and may touch every scene.
    assert_eq!(root.list().await.unwrap().iter().map(|s| s.scene_id).collect::<Vec<_>>(), [id]);
    root.step(id, 2).await.unwrap();
    // Alice's scene is still there after all of bob's attempts, stepped only by root.
    assert_eq!(alice.get(id).await.unwrap().steps, 2);
    lab.server.shutdown().await;
}

#[tokio::test]
async fn a_share_link_watches_but_does_not_steer() {
    let lab = Lab::start(&[("alice", false)], Options::default()).await;
    let mut alice = lab.client("alice").await;
    let id = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let other = alice.create_preset("hydrostatic", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let link = alice.share(id).await.unwrap();
    assert!(link.token.starts_with("floe_shr_"), "{}", link.token);
    assert_eq!(alice.shares(id).await.unwrap(), std::slice::from_ref(&link.share_id));

    let mut viewer = Client::connect_with_token(&lab.server.grpc_url(), Some(&link.token)).await.unwrap();
    assert_eq!(viewer.get(id).await.unwrap().scene_id, id);
    assert_eq!(viewer.list().await.unwrap().iter().map(|s| s.scene_id).collect::<Vec<_>>(), [id]);
    let mut frames = viewer.frames(id, FrameRequest::default()).await.unwrap();
    assert!(frames.next().await.unwrap().is_some(), "a frame for the viewer");
    for (name, c) in grpc_calls(&mut viewer, id).await {
        let watching = ["get", "stats", "frames", "events"].contains(&name);
        let expected = if watching { Code::Ok } else { Code::PermissionDenied };
        assert_eq!(c, expected, "the share link's {name}");
    }
    assert_eq!(code(&viewer.get(other).await.unwrap_err()), Code::NotFound);
    assert_eq!(code(&viewer.create_preset("dam_break", &[]).await.unwrap_err()), Code::PermissionDenied);

    // REST and WebSocket with the link: reading works, steering is 403.
    let bearer = format!("Bearer {}", link.token);
    let auth = [("authorization", bearer.as_str())];
    assert_eq!(http(lab.server.http, "GET", &format!("/api/v1/scenes/{id}"), &auth, "").await.status, 200);
    let a = http(lab.server.http, "POST", &format!("/api/v1/scenes/{id}/step"), &auth, r#"{"steps": 1}"#).await;
    assert_eq!((a.status, a.error().as_str()), (403, "a share link can watch this scene, not steer it"));
    let url = format!("ws://{}/api/v1/scenes/{id}/ws", lab.server.http);
    let (mut ws, response) = tokio_tungstenite::connect_async(ws_request(&url, Some(&link.token))).await.unwrap();
    assert_eq!(response.headers()["sec-websocket-protocol"], "floe.v1");
    ws.send(Message::Text(r#"{"op": "step", "steps": 1}"#.into())).await.unwrap();
    let mut saw = (false, false);
    while !(saw.0 && saw.1) {
        match ws.next().await.unwrap().unwrap() {
            Message::Binary(_) => saw.0 = true,
            Message::Text(t) if t.contains(r#""type":"error""#) => {
                assert!(t.contains("a share link can watch this scene, not steer it"), "{t}");
                saw.1 = true;
            }
            _ => {}
        }
    }

    // Revoked: the link no longer authenticates.
    assert!(alice.revoke_share(id, &link.share_id).await.unwrap().is_empty());
    assert_eq!(code(&viewer.get(id).await.unwrap_err()), Code::Unauthenticated);
    assert_eq!(code(&alice.revoke_share(id, &link.share_id).await.unwrap_err()), Code::NotFound);
    assert_eq!(alice.get(id).await.unwrap().steps, 0, "nothing the link tried steered the scene");
    lab.server.shutdown().await;
}

#[tokio::test]
async fn tokens_admins_and_revocation() {
    let lab = Lab::start(&[("alice", false), ("root", true)], Options::default()).await;
    let url = lab.server.grpc_url();

    // No token, a malformed one, an unknown one: UNAUTHENTICATED / 401.
    let mut anonymous = Client::connect(&url).await.unwrap();
    let e = anonymous.list().await.unwrap_err();
    assert_eq!(code(&e), Code::Unauthenticated);
    assert!(e.to_string().starts_with("this server needs an API token"), "{e}");
    let forged = format!("floe_pat_{}", "0".repeat(64));
    for token in [forged.as_str(), "hunter2"] {
        let mut c = Client::connect_with_token(&url, Some(token)).await.unwrap();
        assert_eq!(code(&c.list().await.unwrap_err()), Code::Unauthenticated, "{token}");
    }
    let a = http(lab.server.http, "GET", "/api/v1/scenes", &[], "").await;
    assert_eq!((a.status, a.header("www-authenticate")), (401, Some("Bearer")));
    assert!(a.error().starts_with("this server needs an API token"), "{}", a.error());
    let a = http(lab.server.http, "GET", "/api/v1/scenes", &[("authorization", "Basic abc")], "").await;
    assert_eq!((a.status, a.error().as_str()), (401, "the authorization header must be 'Bearer <token>'"));
    let ws = format!("ws://{}/api/v1/scenes/1/ws", lab.server.http);
    match tokio_tungstenite::connect_async(ws_request(&ws, None)).await {
        Err(WsError::Http(r)) => assert_eq!(r.status(), 401),
        other => panic!("a WebSocket without a token: {:?}", other.map(|_| ())),
    }
    // The viewer's files need no token.
    assert_eq!(http(lab.server.http, "GET", "/index.html", &[], "").await.status, 200);

    // Admin-only calls: PERMISSION_DENIED / 403 for others.
    let (mut alice, mut root) = (lab.client("alice").await, lab.client("root").await);
    assert_eq!(code(&alice.users().await.unwrap_err()), Code::PermissionDenied);
    assert_eq!(code(&alice.set_quota("alice", "running_scenes", 99).await.unwrap_err()), Code::PermissionDenied);
    let names: Vec<String> = root.users().await.unwrap().into_iter().map(|u| u.name).collect();
    assert_eq!(names, ["alice", "root"]);
    let alice_auth = format!("Bearer {}", lab.token("alice"));
    let root_auth = format!("Bearer {}", lab.token("root"));
    for path in ["/metrics", "/api/v1/users"] {
        assert_eq!(http(lab.server.http, "GET", path, &[("authorization", &alice_auth)], "").await.status, 403);
        assert_eq!(http(lab.server.http, "GET", path, &[("authorization", &root_auth)], "").await.status, 200);
    }
    // The metrics: per scene (read when scraped) and per call, by code.
    let info = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap();
    let (id, particles) = (info.scene_id, info.particles);
    alice.step(id, 3).await.unwrap();
    let metrics = http(lab.server.http, "GET", "/metrics", &[("authorization", &root_auth)], "").await;
    let text = String::from_utf8(metrics.body).unwrap();
    for line in [
        format!("floe_scene_steps_total{{scene=\"{id}\",owner=\"alice\",name=\"dam_break\"}} 3"),
        format!("floe_scene_particles{{scene=\"{id}\",owner=\"alice\",name=\"dam_break\"}} {particles}.0"),
        "floe_requests_total{transport=\"grpc\",method=\"SceneService/Step\",code=\"Ok\"} 1".into(),
        "floe_requests_total{transport=\"grpc\",method=\"LabService/ListUsers\",code=\"PermissionDenied\"} 1".into(),
        "floe_requests_total{transport=\"http\",method=\"GET /metrics\",code=\"403\"} 1".into(),
    ] {
        assert!(text.lines().any(|l| l == line), "no {line} in\n{text}");
    }
    assert!(text.contains("floe_scene_backend_seconds_total{scene="), "no backend time per pass");
    assert_eq!(alice.whoami().await.unwrap().name, "alice");

    // `floe admin token revoke alice`, beside the running server: refused within seconds.
    let location = floe_server::store::Location { data_dir: lab.dir.path().to_path_buf(), database: None };
    let db = location.open_database().await.unwrap();
    db.replace_tokens("alice", None).await.unwrap();
    db.close().await;
    let t0 = std::time::Instant::now();
    while alice.list().await.is_ok() {
        assert!(t0.elapsed().as_secs() < 5, "alice's revoked token still works");
        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    }
    assert_eq!(code(&alice.list().await.unwrap_err()), Code::Unauthenticated);
    lab.server.shutdown().await;
}

#[tokio::test]
async fn websocket_origins_are_checked() {
    let options = Options { origins: vec!["https://dash.example".into()], ..Options::default() };
    let lab = Lab::start(&[("alice", false)], options).await;
    let mut alice = lab.client("alice").await;
    let id = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let url = format!("ws://{}/api/v1/scenes/{id}/ws", lab.server.http);
    let own = format!("http://{}", lab.server.http);
    for (origin, allowed) in [(own.as_str(), true), ("https://dash.example", true), ("http://evil.example", false)] {
        let mut request = ws_request(&url, Some(lab.token("alice")));
        request.headers_mut().insert("origin", origin.parse().unwrap());
        match tokio_tungstenite::connect_async(request).await {
            Ok((mut ws, _)) => {
                assert!(allowed, "{origin} opened a socket");
                ws.close(None).await.unwrap();
            }
            Err(WsError::Http(r)) => {
                assert!(!allowed, "{origin} was refused");
                assert_eq!(r.status(), 403);
                let body: serde_json::Value = serde_json::from_slice(r.body().as_deref().unwrap_or_default()).unwrap();
                assert!(
                    body["error"].as_str().unwrap().starts_with("origin http://evil.example may not open"),
                    "{body}"
                );
            }
            Err(e) => panic!("{origin}: {e}"),
        }
    }
    lab.server.shutdown().await;
}
