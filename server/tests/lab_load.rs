//! A short `floe bench --lab` (the full one is in docs/benchmarks.md): viewers, idle
//! viewers and scripted users on a lab server with users and tokens. No control call
//! may be lost or fail, every reading viewer gets frames, and the server shuts down
//! cleanly. Timings are the benchmark's business, not this test's.

use floe_server::lab_bench::{LoadConfig, run};

#[tokio::test(flavor = "multi_thread")]
async fn no_call_is_lost_under_load() {
    let cfg = LoadConfig {
        floe: env!("CARGO_BIN_EXE_floe").into(),
        backend: "cpu".into(),
        particles: 3000,
        seconds: 5,
        viewers: 12,
        idle_viewers: 3,
        scripts: 4,
        script_rate: 20.0,
    };
    let report = run(&cfg).await.unwrap();
    assert!(report.calls >= 4 * 5 * 10, "only {} calls", report.calls);
    assert_eq!(report.lost, 0, "calls lost");
    assert!(report.errors.is_empty(), "{:?}", report.errors);
    assert!(report.viewer_failures.is_empty(), "{:?}", report.viewer_failures);
    assert!(report.frames >= 9 * 5, "reading viewers got {} frames", report.frames);
    assert!(report.loaded_steps_per_second > 0.0 && report.unloaded_steps_per_second.0 > 0.0);
    assert!(report.clean_shutdown, "floe serve did not shut down cleanly");
}
