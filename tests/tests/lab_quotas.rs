//! Quotas: server-wide defaults, per-user overrides set by an admin; a request over
//! one is RESOURCE_EXHAUSTED / 429 naming the quota and its value, and counted in the
//! metrics.

use common::{Lab, code, http};
use floe_client::FrameRequest;
use floe_server::quota::{Limit, QuotaSet};
use floe_server::service::Options;
use std::time::{Duration, Instant};
use tonic::Code;

mod common;

fn exhausted(e: floe_client::ClientError) -> String {
    assert_eq!(code(&e), Code::ResourceExhausted, "{e}");
    e.to_string().trim_end_matches(" (ResourceExhausted)").to_owned()
}

#[tokio::test]
async fn quotas_are_enforced_per_user_naming_the_quota() {
    let mut defaults = QuotaSet::default();
    defaults.set(Limit::RunningScenes, 1);
    let users = [("alice", false), ("bob", false), ("root", true)];
    let lab = Lab::start(&users, Options { quotas: defaults, ..Options::default() }).await;
    let (mut alice, mut bob, mut root) = (lab.client("alice").await, lab.client("bob").await, lab.client("root").await);

    // Particles per scene: counted before the scene is built.
    root.set_quota("alice", "particles_per_scene", 5000).await.unwrap();
    let e = alice.create_preset("dam_break", &["particle_spacing=0.025"]).await.unwrap_err();
    let expected =
        "quota particles_per_scene = 5000 reached: alice's scenes may have at most 5000 particles; this one has 8000";
    assert_eq!(exhausted(e), expected);
    let alice_auth = format!("Bearer {}", lab.token("alice"));
    let body = r#"{"preset": "dam_break", "overrides": ["particle_spacing=0.025"]}"#;
    let a = http(lab.server.http, "POST", "/api/v1/scenes", &[("authorization", &alice_auth)], body).await;
    assert_eq!((a.status, a.error().as_str()), (429, expected));
    assert!(alice.list().await.unwrap().is_empty());
    bob.create_preset("dam_break", &["particle_spacing=0.025"]).await.expect("bob has the default quota");

    // Running scenes: the server's default of 1, per user.
    let small = ["particle_spacing=0.05"];
    let (a1, a2) = (
        alice.create_preset("dam_break", &small).await.unwrap(),
        alice.create_preset("dam_break", &small).await.unwrap(),
    );
    let (a1, a2) = (a1.scene_id, a2.scene_id);
    alice.run(a1, 0.0).await.unwrap();
    alice.run(a1, 0.0).await.expect("running it again is no new running scene");
    let e = exhausted(alice.run(a2, 0.0).await.unwrap_err());
    assert_eq!(e, "quota running_scenes = 1 reached: alice runs 1 scenes; pause one first");
    let b1 = bob.create_preset("dam_break", &small).await.unwrap().scene_id;
    bob.run(b1, 0.0).await.expect("alice's running scene does not count for bob");
    alice.pause(a1).await.unwrap();
    alice.run(a2, 0.0).await.unwrap();

    // Running particles: 1000 per scene, 1500 allowed.
    root.set_quota("alice", "running_scenes", 5).await.unwrap();
    root.set_quota("alice", "running_particles", 1500).await.unwrap();
    let e = exhausted(alice.run(a1, 0.0).await.unwrap_err());
    assert_eq!(
        e,
        "quota running_particles = 1500 reached: alice's running scenes have 1000 particles and this one 1000"
    );
    alice.pause(a2).await.unwrap();
    alice.run(a1, 0.0).await.unwrap();
    alice.pause(a1).await.unwrap();

    // Open streams: frames, events and WebSockets count; a closed one frees its place.
    root.set_quota("alice", "open_streams", 2).await.unwrap();
    let first = alice.frames(a1, FrameRequest::default()).await.unwrap();
    let _events = alice.events(a1).await.unwrap();
    let e = exhausted(alice.frames(a2, FrameRequest::default()).await.unwrap_err());
    assert_eq!(e, "quota open_streams = 2 reached: alice has 2 streams open; close one first");
    let url = format!("ws://{}/api/v1/scenes/{a1}/ws", lab.server.http);
    match tokio_tungstenite::connect_async(common::ws_request(&url, Some(lab.token("alice")))).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => assert_eq!(r.status(), 429),
        other => panic!("a third stream as a WebSocket: {:?}", other.map(|_| ())),
    }
    drop(first);
    let t0 = Instant::now();
    while alice.frames(a2, FrameRequest::default()).await.is_err() {
        assert!(t0.elapsed() < Duration::from_secs(3), "a closed stream still counts");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }

    // Request rate: a burst over bob's 5 requests per second is refused; alice is not.
    root.set_quota("bob", "requests_per_second", 5).await.unwrap();
    let mut refused = Vec::new();
    for _ in 0..30 {
        if let Err(e) = bob.list().await {
            refused.push(exhausted(e));
        }
    }
    assert!(refused.len() >= 20, "{} of 30 refused", refused.len());
    assert_eq!(refused[0], "quota requests_per_second = 5 reached: bob sends more than 5 requests per second");
    alice.list().await.expect("alice has her own rate");

    // What alice sees of her quotas, and the refusals in the metrics.
    let me = alice.whoami().await.unwrap();
    let q = |n: &str| me.quotas.iter().find(|q| q.name == n).map(|q| (q.value, q.overridden)).unwrap();
    assert_eq!((q("open_streams"), q("running_scenes")), ((2, true), (5, true)));
    assert_eq!(q("requests_per_second"), (Limit::RequestsPerSecond.default_value(), false));
    let root_auth = format!("Bearer {}", lab.token("root"));
    let metrics = http(lab.server.http, "GET", "/metrics", &[("authorization", &root_auth)], "").await;
    let text = String::from_utf8(metrics.body).unwrap();
    for quota in ["particles_per_scene", "running_scenes", "running_particles", "open_streams", "requests_per_second"] {
        let line = format!("floe_quota_refusals_total{{quota=\"{quota}\"}}");
        assert!(text.lines().any(|l| l.starts_with(&line)), "no {line} in the metrics");
    }
    lab.server.shutdown().await;
}
