//! kill -9 the real `floe serve` while scenes run, restart it: every scene is back,
//! paused, at its last checkpoint, and stepping on from it gives the same numbers, bit
//! for bit, as stepping on from that checkpoint in the original process; a scene
//! stepped by hand comes back where the last step call left it, even one killed right
//! after the answer. Then again
//! with the newest checkpoints damaged (a flipped byte, a truncated file): each scene
//! falls back to its previous checkpoint, and says so in the log. On SQLite, and on
//! PostgreSQL when `FLOE_TEST_DATABASE_URL` names a server (tests/run-all.sh starts
//! one; `FLOE_REQUIRE_POSTGRES=1` makes its absence a failure rather than a skip).

use floe_client::Client;
use floe_engine::Simulation;
use floe_server::lab_bench::process::{Data, ServerProcess, add_user, fresh_database};
use floe_server::store::Checkpoints;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Starts `floe serve` on `data`, checkpointing running scenes every second.
fn start(data: &Data, log: PathBuf) -> ServerProcess {
    let floe = Path::new(env!("CARGO_BIN_EXE_floe"));
    ServerProcess::start(floe, data, &["--scene", "none", "--backend", "cpu", "--checkpoint-every", "1"], log).unwrap()
}

/// The checkpoint files of a scene, newest first.
fn checkpoints(dir: &Path, scene: u64) -> Vec<PathBuf> {
    Checkpoints::open(dir.join("checkpoints")).unwrap().files(scene).into_iter().map(|f| f.1).collect()
}

/// The state `steps` steps on from a snapshot, stepped in this process.
fn stepped_on(snapshot: &[u8], steps: u32) -> Vec<u8> {
    let mut sim = Simulation::restore(snapshot).unwrap();
    for _ in 0..steps {
        sim.step().unwrap();
    }
    sim.snapshot()
}

async fn crash_and_recover(database: Option<&str>) {
    let dir = tempfile::tempdir().unwrap();
    let data = Data { dir: dir.path().join("data"), database: database.map(str::to_owned) };
    let token = add_user(Path::new(env!("CARGO_BIN_EXE_floe")), &data, "alice").unwrap();
    let server = start(&data, dir.path().join("first.log"));
    let mut c = Client::connect_with_token(&server.grpc, Some(&token)).await.unwrap();

    // A: stepped by hand to 20, 50 and 80, each call checkpointed before its answer.
    let a = c.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap().scene_id;
    c.step(a, 20).await.unwrap();
    let newest = |dir: &Path| Checkpoints::read(&checkpoints(dir, a)[0]).unwrap();
    assert_eq!(newest(&data.dir).0.step, 20, "the first step call is checkpointed before its answer");
    c.step(a, 30).await.unwrap();
    c.step(a, 30).await.unwrap();
    let at_80 = c.snapshot(a).await.unwrap();
    // B: live settings changed, then running, checkpointed every second of running.
    let b = c.create_preset("hydrostatic", &["particle_spacing=0.05"]).await.unwrap().scene_id;
    c.set_parameters(b, &["gravity=[0,-5,0]"]).await.unwrap();
    c.run(b, 0.0).await.unwrap();
    // C: never stepped, never checkpointed.
    let fresh = c.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    // D: stepped by hand at the last moment.
    let d = c.create_preset("hydrostatic", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    let t0 = Instant::now();
    while checkpoints(&data.dir, b).len() < 2 || newest(&data.dir).0.step < 80 {
        assert!(t0.elapsed() < Duration::from_secs(30), "no periodic checkpoints of a running scene");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    c.step(d, 20).await.unwrap();
    let d_at_20 = c.snapshot(d).await.unwrap();
    server.kill().unwrap();

    // Restart: everything is back, paused, at its newest checkpoint.
    let b_newest = Checkpoints::read(&checkpoints(&data.dir, b)[0]).unwrap();
    let server = start(&data, dir.path().join("second.log"));
    let mut c = Client::connect_with_token(&server.grpc, Some(&token)).await.unwrap();
    let scenes = c.list().await.unwrap();
    assert_eq!(scenes.iter().map(|s| s.scene_id).collect::<Vec<_>>(), [a, b, fresh, d]);
    assert!(scenes.iter().all(|s| s.state == floe_proto::pb::SceneState::Paused as i32), "{scenes:?}");
    assert_eq!(c.get(a).await.unwrap().steps, 80, "A comes back where its last step call left it");
    c.step(a, 30).await.unwrap();
    let at_110 = c.snapshot(a).await.unwrap();
    assert!(at_110 == stepped_on(&at_80, 30), "scene A did not step on as in the original process");
    assert_eq!(c.get(d).await.unwrap().steps, 20, "D comes back at the step its caller was told of");
    c.step(d, 5).await.unwrap();
    assert!(c.snapshot(d).await.unwrap() == stepped_on(&d_at_20, 5), "scene D did not step on bit for bit");
    let info = c.get(b).await.unwrap();
    assert_eq!(info.steps, b_newest.0.step);
    assert!(info.scene_json.contains("-5.0"), "live settings kept: {}", info.scene_json);
    c.step(b, 10).await.unwrap();
    assert!(c.snapshot(b).await.unwrap() == stepped_on(&b_newest.1, 10), "scene B did not step on from its checkpoint");
    assert_eq!(c.get(fresh).await.unwrap().steps, 0);
    let next = c.create_preset("dam_break", &["particle_spacing=0.1"]).await.unwrap().scene_id;
    assert!(next > fresh, "scene ids are never reused");
    let log = server.kill().unwrap();
    assert!(log.contains("scene restored paused at step 80"), "{log}");

    // Damage: A's newest checkpoint gets a flipped byte, B's newest is cut short.
    let a_files = checkpoints(&data.dir, a);
    let mut bytes = std::fs::read(&a_files[0]).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x40;
    std::fs::write(&a_files[0], bytes).unwrap();
    let b_files = checkpoints(&data.dir, b);
    let length = std::fs::metadata(&b_files[0]).unwrap().len();
    std::fs::OpenOptions::new().write(true).open(&b_files[0]).unwrap().set_len(length / 3).unwrap();

    let server = start(&data, dir.path().join("third.log"));
    let mut c = Client::connect_with_token(&server.grpc, Some(&token)).await.unwrap();
    // A's newest checkpoint is the one its step to 110 wrote: it falls back to 80.
    assert_eq!(c.get(a).await.unwrap().steps, 80, "A falls back to its checkpoint at step 80");
    c.step(a, 30).await.unwrap();
    assert!(c.snapshot(a).await.unwrap() == at_110, "scene A did not step on from its previous checkpoint");
    // B's newest is the one its step of 10 wrote: it falls back to the periodic one.
    assert_eq!(c.get(b).await.unwrap().steps, b_newest.0.step, "B falls back to its previous checkpoint");
    c.step(b, 3).await.unwrap();
    assert!(c.snapshot(b).await.unwrap() == stepped_on(&b_newest.1, 3));
    // A graceful stop checkpoints every scene.
    assert!(server.terminate().unwrap(), "floe serve exited with an error");
    let log = std::fs::read_to_string(dir.path().join("third.log")).unwrap();
    assert!(log.contains("checksum mismatch: the file is damaged"), "{log}");
    assert!(log.contains("cut short"), "{log}");
    let newest = Checkpoints::read(&checkpoints(&data.dir, a)[0]).unwrap().0;
    assert_eq!(newest.step, 110, "the shutdown checkpointed A where it was");
}

#[tokio::test(flavor = "multi_thread")]
async fn kill_9_and_damaged_checkpoints_on_sqlite() {
    crash_and_recover(None).await;
}

#[tokio::test(flavor = "multi_thread")]
async fn kill_9_and_damaged_checkpoints_on_postgres() {
    let Some(base) = std::env::var("FLOE_TEST_DATABASE_URL").ok().filter(|u| !u.is_empty()) else {
        if std::env::var_os("FLOE_REQUIRE_POSTGRES").is_some() {
            panic!("FLOE_REQUIRE_POSTGRES is set but FLOE_TEST_DATABASE_URL is not");
        }
        return eprintln!("SKIPPED kill_9_and_damaged_checkpoints_on_postgres: FLOE_TEST_DATABASE_URL is not set");
    };
    let url = fresh_database(&base, "crash").await.unwrap();
    crash_and_recover(Some(&url)).await;
}
