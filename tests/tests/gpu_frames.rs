//! Frames from a scene on the GPU backend: positions quantised on the device
//! decode to within the header's stated error of the scene's state, and a GPU
//! scene's snapshot restores on the CPU; the GPU benchmark suite runs at tiny
//! sizes. Skipped (saying why) without a GPU;
//! CI runs it on Mesa's lavapipe.

use floe_engine::Simulation;
use floe_proto::{Decoder, Limits};
use floe_server::auth::Caller;
use floe_server::service::options::FrameRequest;
use floe_server::service::{Registry, SceneSource};

#[tokio::test]
async fn frames_of_a_gpu_scene_decode_within_their_stated_error() {
    let backend = match floe_gpu::select::select(floe_gpu::BackendChoice::Gpu) {
        Ok(b) => b,
        Err(e) if std::env::var_os("FLOE_REQUIRE_GPU").is_some() => panic!("FLOE_REQUIRE_GPU is set: {e}"),
        Err(e) => return eprintln!("SKIPPED frames_of_a_gpu_scene_decode_within_their_stated_error: no GPU ({e})"),
    };
    let registry = Registry::new(Default::default(), backend.factory);
    let local = Caller::local();
    let preset = SceneSource::Preset("dam_break".into());
    let scene = registry.create(&local, preset, vec!["particle_spacing=0.05".into()]).await.unwrap();
    assert_eq!(scene.shared.backend, "gpu");
    scene.step(25, None).await.unwrap();
    let request = FrameRequest {
        channels: vec!["velocity".into()],
        max_fps: Some(240.0),
        mode: Some("identity".into()),
        ..FrameRequest::default()
    };
    let mut frames = registry.subscribe(&local, scene.shared.id, &request).unwrap().spawn(|f| f);
    let frame = frames.recv().await.unwrap().unwrap();
    let decoded = Decoder::new(Limits::default()).decode(&frame.data).unwrap();
    // The scene's exact state, through a snapshot restored on the CPU backend.
    let state = Simulation::restore(&scene.save().await.unwrap()).unwrap().read(&["velocity"]);
    assert_eq!(decoded.header.step, 25);
    assert_eq!(decoded.positions.len(), state.positions.len());
    let max_error = decoded.header.channels[0].ranges.iter().map(|r| r.max_error).fold(0.0, f32::max);
    let worst = decoded
        .positions
        .iter()
        .zip(&state.positions)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0, f32::max);
    assert!(worst <= max_error * 1.01, "decoded positions off by {worst} m; the header states {max_error} m");
    let v = decoded.named("velocity").expect("velocity channel");
    assert_eq!(v.len(), state.positions.len());
    registry.shutdown().await;
}

/// `floe bench --suite gpu --tiny`: every figure of the GPU suite runs at a small
/// size and is written as a table and JSON, each with its real-time factor or
/// throughput, so the command a GPU machine runs never rots.
#[test]
fn the_gpu_suite_runs_at_tiny_sizes() {
    if let Err(e) = floe_gpu::select::select(floe_gpu::BackendChoice::Gpu) {
        if std::env::var_os("FLOE_REQUIRE_GPU").is_some() {
            panic!("FLOE_REQUIRE_GPU is set: {e}");
        }
        return eprintln!("SKIPPED the_gpu_suite_runs_at_tiny_sizes: no GPU ({e})");
    }
    use clap::Parser;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let cli =
        floe_server::cli::Cli::try_parse_from(["floe", "bench", "--suite", "gpu", "--tiny", "--out", out]).unwrap();
    floe_server::execute(cli).unwrap();
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("gpu-suite.json")).unwrap()).unwrap();
    let names: Vec<&str> = report["rows"].as_array().unwrap().iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["dam_break", "bunny", "ice_melting", "avalanche", "flakes"]);
    for row in report["rows"].as_array().unwrap() {
        assert!(row["steps"].as_u64().unwrap() > 0 && row["m_steps_per_second"].as_f64().unwrap() > 0.0, "{row}");
    }
    let table = std::fs::read_to_string(dir.path().join("gpu-suite.md")).unwrap();
    assert!(table.contains("| bunny |") && table.contains("tiny sizes"), "{table}");
}
