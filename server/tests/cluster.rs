//! Three `floe serve --worker` processes on one PostgreSQL database and one shared
//! data directory: new scenes created at once spread over the workers by placement,
//! any worker lists every scene's figures and every worker's totals, a call for a
//! scene on another worker names that worker, the running-scene quota counts every
//! worker's scenes; kill -9 a worker and its scene is back, paused, on another,
//! stepping on bit for bit from its last checkpoint; a worker stopped (SIGSTOP) past
//! its lease and continued writes nothing for the scene that moved.
//! Needs `FLOE_TEST_DATABASE_URL` (tests/run-all.sh starts a server;
//! `FLOE_REQUIRE_POSTGRES=1` makes its absence a failure rather than a skip).

use floe_client::{Client, ClientError};
use floe_engine::Simulation;
use floe_server::lab_bench::process::{Data, ServerProcess, admin, fresh_database};
use floe_server::store::Checkpoints;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The lease of the test's workers (s): short, so a failover is seconds away.
const LEASE: u64 = 3;

struct Worker {
    name: &'static str,
    process: ServerProcess,
}

fn start(data: &Data, name: &str, log: PathBuf) -> ServerProcess {
    let floe = Path::new(env!("CARGO_BIN_EXE_floe"));
    let lease = LEASE.to_string();
    let args = [
        "--scene",
        "none",
        "--backend",
        "cpu",
        "--auth",
        "off",
        "--checkpoint-every",
        "1",
        "--worker",
        name,
        "--lease",
        &lease,
        "--quota",
        "running_scenes=2",
    ];
    ServerProcess::start(floe, data, &args, log).unwrap()
}

/// The worker a refused call names in its `floe-worker` metadata.
fn named_worker(e: &ClientError) -> Option<String> {
    let ClientError::Status(s) = e else { return None };
    (s.code() == tonic::Code::Unavailable)
        .then(|| s.metadata().get("floe-worker")?.to_str().ok().map(str::to_owned))
        .flatten()
}

/// The state `steps` steps on from a snapshot, stepped in this process.
fn stepped_on(snapshot: &[u8], steps: u32) -> Vec<u8> {
    let mut sim = Simulation::restore(snapshot).unwrap();
    for _ in 0..steps {
        sim.step().unwrap();
    }
    sim.snapshot()
}

/// Polls `f` every 100 ms until it gives a value, for at most `limit`.
async fn within<T>(limit: Duration, what: &str, mut f: impl AsyncFnMut() -> Option<T>) -> T {
    let t0 = Instant::now();
    loop {
        if let Some(v) = f().await {
            return v;
        }
        assert!(t0.elapsed() < limit, "not within {limit:?}: {what}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// Which live worker holds `scene` (asking each directly), with a client on it.
async fn holder(workers: &[&Worker], scene: u64) -> Option<(&'static str, Client)> {
    for w in workers {
        let mut c = Client::connect(&w.process.grpc).await.ok()?;
        if c.get(scene).await.is_ok() {
            return Some((w.name, c));
        }
    }
    None
}

/// Creates an equal scene through the worker `through`, following placement's
/// answer to the worker it names with the `floe-worker` header (as the clients do
/// through the proxy); the scene's id and the worker that built it.
async fn create(address: &impl Fn(&str) -> String, through: &str) -> (u64, String) {
    use floe_proto::pb::{self, scene_service_client::SceneServiceClient};
    let request = || pb::CreateSceneRequest {
        source: Some(pb::create_scene_request::Source::Preset("dam_break".into())),
        document_format: String::new(),
        overrides: vec!["particle_spacing=0.05".into()],
        backend: String::new(),
    };
    let connect = async |to: &str| {
        SceneServiceClient::new(tonic::transport::Endpoint::from_shared(address(to)).unwrap().connect().await.unwrap())
    };
    let mut client = connect(through).await;
    match client.create_scene(request()).await {
        Ok(info) => (info.into_inner().scene_id, through.to_string()),
        Err(s) => {
            let to = named_worker(&ClientError::Status(s.clone())).unwrap_or_else(|| panic!("not a redirect: {s:?}"));
            let mut named = tonic::Request::new(request());
            named.metadata_mut().insert("floe-worker", to.parse().unwrap());
            let mut client = connect(&to).await;
            (client.create_scene(named).await.unwrap().into_inner().scene_id, to)
        }
    }
}

/// The body of `GET path` from `http` (`HOST:PORT`).
async fn get(http: &str, path: &str) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut s = tokio::net::TcpStream::connect(http).await.unwrap();
    s.write_all(format!("GET {path} HTTP/1.1\r\nhost: {http}\r\nconnection: close\r\n\r\n").as_bytes()).await.unwrap();
    let mut raw = String::new();
    s.read_to_string(&mut raw).await.unwrap();
    raw.split_once("\r\n\r\n").expect("a complete answer").1.to_string()
}

#[tokio::test(flavor = "multi_thread")]
async fn three_workers_place_fail_over_and_fence() {
    let Some(base) = std::env::var("FLOE_TEST_DATABASE_URL").ok().filter(|u| !u.is_empty()) else {
        if std::env::var_os("FLOE_REQUIRE_POSTGRES").is_some() {
            panic!("FLOE_REQUIRE_POSTGRES is set but FLOE_TEST_DATABASE_URL is not");
        }
        return eprintln!("SKIPPED three_workers_place_fail_over_and_fence: FLOE_TEST_DATABASE_URL is not set");
    };
    let dir = tempfile::tempdir().unwrap();
    let data = Data { dir: dir.path().join("shared"), database: Some(fresh_database(&base, "cluster").await.unwrap()) };
    let names = ["w1", "w2", "w3"];
    let workers: Vec<Worker> = names
        .iter()
        .map(|&name| Worker { name, process: start(&data, name, dir.path().join(format!("{name}.log"))) })
        .collect();
    let addresses: Vec<(&str, String)> = workers.iter().map(|w| (w.name, w.process.grpc.clone())).collect();
    let address = move |name: &str| addresses.iter().find(|w| w.0 == name).unwrap().1.clone();

    // Six equal scenes created at once, two through each worker, each following
    // placement's answer to the worker it names: placements take turns and reserve
    // room, so two land on each worker. A, B and C: the first on w1, w2 and w3.
    let mut creations = tokio::task::JoinSet::new();
    for through in ["w1", "w2", "w3", "w1", "w2", "w3"] {
        let address = address.clone();
        creations.spawn(async move { create(&address, through).await });
    }
    let mut placed: Vec<(u64, String)> = creations.join_all().await;
    placed.sort();
    let mut on: Vec<&str> = placed.iter().map(|p| p.1.as_str()).collect();
    on.sort_unstable();
    assert_eq!(on, ["w1", "w1", "w2", "w2", "w3", "w3"], "equal scenes spread over equal workers: {placed:?}");
    let first_on = |w: &str| placed.iter().find(|p| p.1 == w).unwrap().0;
    let (a, b, c) = (first_on("w1"), first_on("w2"), first_on("w3"));
    let mut first = Client::connect(&address("w1")).await.unwrap();

    // A scene asking for a backend no worker runs is refused, naming what they run.
    let mut on_gpu = Client::connect(&address("w1")).await.unwrap();
    on_gpu.set_backend("gpu");
    let e = on_gpu.create_preset("dam_break", &["particle_spacing=0.05"]).await.unwrap_err();
    let ClientError::Status(s) = &e else { panic!("{e}") };
    assert_eq!(s.code(), tonic::Code::FailedPrecondition, "{s:?}");
    assert_eq!(s.message(), "backend: no worker of this cluster runs the gpu backend (they run cpu)");

    // A call for B through w1 names w2 (once w1's tick has seen B).
    let named =
        within(Duration::from_secs(5), "w1 names B's worker", async || named_worker(&first.get(b).await.err()?)).await;
    assert_eq!(named, "w2");

    // The running-scene quota (2) counts scenes on every worker.
    let mut on_w2 = Client::connect(&address("w2")).await.unwrap();
    let mut on_w3 = Client::connect(&address("w3")).await.unwrap();
    first.run(a, 0.0).await.unwrap();
    on_w3.run(c, 0.0).await.unwrap();
    let e = on_w2.run(b, 0.0).await.unwrap_err();
    let ClientError::Status(s) = &e else { panic!("{e}") };
    assert_eq!(s.code(), tonic::Code::ResourceExhausted, "{s:?}");

    // Any worker lists every scene with its worker and its figures as published with
    // its worker's last heartbeat (C runs on w3), and its /metrics has every worker's
    // totals.
    let stats = within(Duration::from_secs(5), "w1's stats show C running on w3", async || {
        let stats = first.all_stats().await.ok()?;
        let c_stats = stats.iter().find(|s| s.scene_id == c)?;
        (c_stats.steps > 0 && c_stats.steps_per_second > 0.0).then_some(stats)
    })
    .await;
    let mut listed: Vec<(u64, &str)> = stats.iter().map(|s| (s.scene_id, s.worker.as_str())).collect();
    listed.sort_unstable();
    assert_eq!(listed, placed.iter().map(|p| (p.0, p.1.as_str())).collect::<Vec<_>>());
    let http = workers[0].process.http.clone();
    let wanted: Vec<String> = names
        .iter()
        .map(|w| format!("floe_cluster_scenes{{worker=\"{w}\"}} 2"))
        .chain([r#"floe_cluster_running_scenes{worker="w3"} 1"#.to_string()])
        .collect();
    within(Duration::from_secs(5), "every worker's totals in w1's /metrics", async || {
        let metrics = get(&http, "/metrics").await;
        wanted.iter().all(|line| metrics.lines().any(|l| l == line)).then_some(())
    })
    .await;
    first.pause(a).await.unwrap();

    // B stepped by hand to 20 (checkpointed before the answer), then kill -9 w2.
    on_w2.step(b, 20).await.unwrap();
    let b_at_20 = on_w2.snapshot(b).await.unwrap();
    let mut workers = workers;
    let w2 = workers.remove(1);
    w2.process.kill().unwrap();
    let t0 = Instant::now();
    let live: Vec<&Worker> = workers.iter().collect();
    let (to, mut on_new) =
        within(Duration::from_secs(3 * LEASE + 5), "B back on a live worker", async || holder(&live, b).await).await;
    eprintln!("B is back on {to} {:.1} s after w2's kill -9", t0.elapsed().as_secs_f64());
    let info = on_new.get(b).await.unwrap();
    assert_eq!(info.state, floe_proto::pb::SceneState::Paused as i32, "a moved scene comes back paused");
    assert_eq!(info.steps, 20, "from its last checkpoint");
    on_new.step(b, 10).await.unwrap();
    assert!(on_new.snapshot(b).await.unwrap() == stepped_on(&b_at_20, 10), "B did not step on bit for bit");
    for w in &live {
        let mut on = Client::connect(&w.process.grpc).await.unwrap();
        assert_eq!(on.get(b).await.is_ok(), w.name == to, "B is held by {to} only");
        let listed = within(Duration::from_secs(5), "every list names B's worker", async || {
            let list = on.list().await.ok()?;
            list.into_iter().find(|s| s.scene_id == b && s.worker == to)
        })
        .await;
        assert_eq!(listed.worker, to);
    }

    // w3 (running C) stopped past its lease: C moves to w1, paused. Continued, w3
    // writes nothing for C.
    let w3 = workers.iter().find(|w| w.name == "w3").unwrap();
    let w1 = workers.iter().find(|w| w.name == "w1").unwrap();
    w3.process.signal("STOP").unwrap();
    let mut on_w1 = within(Duration::from_secs(3 * LEASE + 5), "C on w1", async || holder(&[w1], c).await).await.1;
    assert_eq!(on_w1.get(c).await.unwrap().state, floe_proto::pb::SceneState::Paused as i32);
    let files = || {
        Checkpoints::open(data.dir.join("checkpoints"))
            .unwrap()
            .files(c)
            .into_iter()
            .map(|(seq, path)| (seq, std::fs::metadata(path).unwrap().modified().unwrap()))
            .collect::<Vec<_>>()
    };
    // w1 checkpoints C as it takes it up, in C's new placement generation.
    let before = within(Duration::from_secs(5), "w1's first checkpoint of C", async || {
        let files = files();
        (files.first()?.0.0 >= 1).then_some(files)
    })
    .await;
    // A call sent to w3 while it is stopped: it meets w3 as it wakes, before or
    // after w3 learns it lost C, and is refused either way (the pause would write a
    // checkpoint).
    let mut late = Client::connect(&w3.process.grpc).await.unwrap();
    let late_pause = tokio::spawn(async move { late.pause(c).await });
    tokio::time::sleep(Duration::from_millis(300)).await;
    w3.process.signal("CONT").unwrap();
    let refused = late_pause.await.unwrap().unwrap_err();
    let ClientError::Status(s) = &refused else { panic!("{refused}") };
    assert_eq!(s.code(), tonic::Code::Unavailable, "{s:?}");
    let log = within(Duration::from_secs(10), "w3 learns it was evicted", async || {
        let log = std::fs::read_to_string(&w3.process.log).unwrap();
        log.contains("declared gone by the cluster").then_some(log)
    })
    .await;
    tokio::time::sleep(Duration::from_secs(2)).await;
    assert_eq!(files(), before, "the late worker wrote a checkpoint of a scene that moved:\n{log}");
    assert!(holder(&[w3], c).await.is_none(), "the late worker dropped C");
    assert_eq!(on_w1.get(c).await.unwrap().state, floe_proto::pb::SceneState::Paused as i32);
    on_w1.step(c, 2).await.unwrap();

    // Draining w1 for maintenance moves its scenes to w3 (joined again, holding
    // nothing), paused, stepping on bit for bit from where they were.
    let a_before = on_w1.snapshot(a).await.unwrap();
    let c_before = on_w1.snapshot(c).await.unwrap();
    let out = admin(Path::new(env!("CARGO_BIN_EXE_floe")), &data, &["worker", "drain", "w1"]).unwrap();
    assert!(out.is_empty(), "drain prints its message on stderr: {out}");
    for (scene, before) in [(a, a_before), (c, c_before)] {
        let mut on_w3 =
            within(Duration::from_secs(15), "a drained scene on w3", async || holder(&[w3], scene).await).await.1;
        assert_eq!(on_w3.get(scene).await.unwrap().state, floe_proto::pb::SceneState::Paused as i32);
        on_w3.step(scene, 3).await.unwrap();
        assert!(
            on_w3.snapshot(scene).await.unwrap() == stepped_on(&before, 3),
            "scene {scene} changed on its way to w3"
        );
    }
    let listed = admin(Path::new(env!("CARGO_BIN_EXE_floe")), &data, &["worker", "list"]).unwrap();
    let w1_row = listed.lines().find(|l| l.starts_with("w1 ")).unwrap_or_else(|| panic!("{listed}"));
    assert!(w1_row.contains("draining"), "{listed}");
}
