//! The cluster through its proxy, as a user meets it: tests/cluster.sh starts
//! PostgreSQL, nginx and three workers on loopback (deploy/local/cluster.sh) and runs
//! this with their addresses. The Rust client creates scenes through the proxy alone,
//! they land one on each worker, every call follows its scene to its worker, the
//! list from any entry point names every scene's worker, and a frame stream follows
//! its scene when its worker is killed (kill -9). Without the cluster's addresses the
//! test is skipped (`FLOE_REQUIRE_CLUSTER=1` makes that a failure).

use floe_client::{Client, FrameRequest};
use std::collections::BTreeSet;
use std::time::{Duration, Instant};

fn env(name: &str) -> Option<String> {
    std::env::var(name).ok().filter(|v| !v.is_empty())
}

#[tokio::test(flavor = "multi_thread")]
async fn every_call_and_stream_through_the_proxy() {
    let Some(proxy) = env("FLOE_PROXY_GRPC") else {
        if std::env::var_os("FLOE_REQUIRE_CLUSTER").is_some() {
            panic!("FLOE_REQUIRE_CLUSTER is set but FLOE_PROXY_GRPC is not (run tests/cluster.sh)");
        }
        return eprintln!("SKIPPED every_call_and_stream_through_the_proxy: no cluster (tests/cluster.sh runs it)");
    };
    let mut c = Client::connect(&proxy).await.unwrap();
    let mut ids = Vec::new();
    for _ in 0..3 {
        ids.push(c.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap().scene_id);
    }
    // Every call follows its scene to its worker.
    for &id in &ids {
        assert_eq!(c.step(id, 5).await.unwrap().steps, 5);
        assert_eq!(c.get(id).await.unwrap().steps, 5);
        assert!(!c.snapshot(id).await.unwrap().is_empty());
        c.set_parameters(id, &["gravity=[0,-9,0]"]).await.unwrap();
        c.checkpoint(id).await.unwrap();
    }
    // The list from whichever worker the proxy picks names every scene's worker.
    let t0 = Instant::now();
    let placed = loop {
        let list = c.list().await.unwrap();
        let placed: Vec<(u64, String)> =
            list.iter().filter(|s| ids.contains(&s.scene_id)).map(|s| (s.scene_id, s.worker.clone())).collect();
        if placed.len() == 3 && placed.iter().all(|p| !p.1.is_empty()) {
            break placed;
        }
        assert!(t0.elapsed() < Duration::from_secs(10), "the list does not name every scene's worker: {list:?}");
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    let workers: BTreeSet<&str> = placed.iter().map(|p| p.1.as_str()).collect();
    assert_eq!(workers, BTreeSet::from(["floe-1", "floe-2", "floe-3"]), "one scene on each worker: {placed:?}");

    // A stream of floe-2's scene follows it when floe-2 is killed.
    let (victim, _) = placed.iter().find(|p| p.1 == "floe-2").unwrap().clone();
    c.run(victim, 1.0).await.unwrap();
    let mut frames = c.frames(victim, FrameRequest::default()).await.unwrap();
    assert!(frames.next().await.unwrap().is_some());
    let pid = env("FLOE_CLUSTER_WORKER_2_PID").expect("the cluster's pids");
    assert!(std::process::Command::new("kill").args(["-KILL", &pid]).status().unwrap().success());
    let t0 = Instant::now();
    // Reads (here the list) wait for the cluster to move the scene; while it moves, the
    // list may name no worker for it (or leave it out), as at placement above.
    let now = loop {
        let list = c.list().await.unwrap();
        let now = list.iter().find(|s| s.scene_id == victim).map(|s| s.worker.clone()).unwrap_or_default();
        if !now.is_empty() && now != "floe-2" {
            break now;
        }
        assert!(t0.elapsed() < Duration::from_secs(30), "scene {victim} still on floe-2 after 30 s");
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    assert!(matches!(now.as_str(), "floe-1" | "floe-3"), "{now:?}");
    let info = c.get(victim).await.unwrap();
    assert_eq!(info.state, floe_proto::pb::SceneState::Paused as i32, "a moved scene comes back paused");
    eprintln!("scene {victim} on {now} {:.1} s after floe-2's kill -9", t0.elapsed().as_secs_f64());
    // The same stream, reopened by the client on the new worker, shows the steps taken there.
    // A change is not repeated by the client on a bare UNAVAILABLE (the proxy may have
    // sent it to the dead worker once more): the caller retries, as users do.
    let stepped = within_retries(async || c.step(victim, 3).await).await.steps;
    let t1 = Instant::now();
    loop {
        let frame = tokio::time::timeout(Duration::from_secs(30), frames.next()).await.expect("no frame within 30 s");
        let frame = frame.unwrap().expect("the stream ended instead of following the scene");
        if frame.header.step == stepped {
            break;
        }
        assert!(t1.elapsed() < Duration::from_secs(30), "no frame of step {stepped} from the scene's new worker");
    }
    for &id in &ids {
        c.delete(id).await.unwrap();
    }
}

/// `f` until it succeeds, for at most 10 s, retrying only UNAVAILABLE.
async fn within_retries<T>(mut f: impl AsyncFnMut() -> Result<T, floe_client::ClientError>) -> T {
    let t0 = Instant::now();
    loop {
        match f().await {
            Ok(v) => return v,
            Err(floe_client::ClientError::Status(s))
                if s.code() == tonic::Code::Unavailable && t0.elapsed() < Duration::from_secs(10) =>
            {
                tokio::time::sleep(Duration::from_millis(250)).await;
            }
            Err(e) => panic!("{e}"),
        }
    }
}
