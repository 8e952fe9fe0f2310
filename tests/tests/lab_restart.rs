//! A graceful restart loses nothing: scenes come back paused where they were (with
//! their owners and live settings), share links and quota overrides still hold, a
//! deleted scene stays deleted and ids are never reused. (A crash, kill -9, is
//! tested with the real binary in `server/tests/crash_recovery.rs`.)

use common::{Lab, code};
use floe_server::service::Options;
use tonic::Code;

mod common;

#[tokio::test]
async fn a_restart_brings_back_what_users_made() {
    let lab = Lab::start(&[("alice", false), ("root", true)], Options::default()).await;
    let (mut alice, mut root) = (lab.client("alice").await, lab.client("root").await);
    let stepped = alice.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap().scene_id;
    alice.step(stepped, 12).await.unwrap();
    alice.set_parameters(stepped, &["gravity=[0,-1.62,0]", "fluids[0].xsph=0.1"]).await.unwrap();
    alice.step(stepped, 3).await.unwrap();
    let running = alice.create_preset("hydrostatic", &["particle_spacing=0.05"]).await.unwrap().scene_id;
    alice.run(running, 0.0).await.unwrap();
    let deleted = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    alice.delete(deleted).await.unwrap();
    let link = alice.share(stepped).await.unwrap();
    root.set_quota("alice", "open_streams", 7).await.unwrap();
    tokio::time::sleep(std::time::Duration::from_millis(200)).await;
    // The state at shutdown, which the shutdown's checkpoint must keep.
    let before = alice.snapshot(stepped).await.unwrap();

    let lab = lab.restart().await;
    let mut alice = lab.client("alice").await;
    let ids: Vec<u64> = alice.list().await.unwrap().iter().map(|s| s.scene_id).collect();
    assert_eq!(ids, [stepped, running]);
    let info = alice.get(stepped).await.unwrap();
    assert_eq!((info.steps, info.owner.as_str(), info.state), (15, "alice", 1));
    assert!(info.scene_json.contains("-1.62"), "live settings kept: {}", info.scene_json);
    // Stepping on gives the numbers stepping on from the state at shutdown gives.
    let mut expected = floe_engine::Simulation::restore(&before).unwrap();
    for _ in 0..5 {
        expected.step().unwrap();
    }
    alice.step(stepped, 5).await.unwrap();
    assert!(alice.snapshot(stepped).await.unwrap() == expected.snapshot(), "not the same state, bit for bit");
    let run = alice.get(running).await.unwrap();
    assert!(run.steps > 0, "the running scene kept its progress");
    assert_eq!(run.state, floe_proto::pb::SceneState::Paused as i32, "it comes back paused");
    assert_eq!(code(&alice.get(deleted).await.unwrap_err()), Code::NotFound);
    let next = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    assert!(next > deleted, "ids are never reused: {next} after {deleted}");

    let mut viewer = floe_client::Client::connect_with_token(&lab.server.grpc_url(), Some(&link.token)).await.unwrap();
    assert_eq!(viewer.get(stepped).await.unwrap().steps, 20);
    let me = alice.whoami().await.unwrap();
    assert!(me.quotas.iter().any(|q| q.name == "open_streams" && q.value == 7 && q.overridden));
    assert!(
        !lab.dir.path().join("checkpoints").join(deleted.to_string()).exists(),
        "a deleted scene's checkpoints are removed"
    );
    lab.server.shutdown().await;
}

/// A step call that advanced a paused scene is checkpointed before its answer (over
/// gRPC, REST and the WebSocket alike; `server/tests/crash_recovery.rs` kills the
/// server right after one): the checkpoint on disk is at the stepped step when the
/// answer arrives. A second call within a second of it is written by the
/// maintenance loop (once a second) a second after the first at the latest.
#[tokio::test]
async fn a_step_call_is_checkpointed_before_its_answer() {
    let lab = Lab::start(&[("alice", false)], Options::default()).await;
    let mut alice = lab.client("alice").await;
    let newest = |id: u64| {
        let checkpoints = floe_server::store::Checkpoints::open(lab.dir.path().join("checkpoints")).unwrap();
        checkpoints.files(id).first().map(|(_, path)| floe_server::store::Checkpoints::read(path).unwrap().0.step)
    };
    let id = alice.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    assert_eq!(newest(id), None, "a new scene has no checkpoint");
    let auth = format!("Bearer {}", lab.token("alice"));
    let answer = common::http(
        lab.server.http,
        "POST",
        &format!("/api/v1/scenes/{id}/step"),
        &[("authorization", &auth)],
        r#"{"steps": 7}"#,
    )
    .await;
    assert_eq!(answer.status, 200, "{}", answer.error());
    assert_eq!(newest(id), Some(7), "REST: checkpointed before the answer");
    alice.step(id, 3).await.unwrap();
    let t0 = std::time::Instant::now();
    while newest(id) != Some(10) {
        assert!(t0.elapsed() < std::time::Duration::from_secs(5), "the second step call was never checkpointed");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    assert!(t0.elapsed() < std::time::Duration::from_millis(2500), "written by the next maintenance tick");
    lab.server.shutdown().await;
}
