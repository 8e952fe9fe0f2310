//! `floectl` as a user drives it, against a real server on port 0: every command, a recording
//! exported with no server running, and the errors bad input gets.

mod common;

use clap::Parser;
use common::TestServer;
use floe_client::Client;
use floe_client::cli::{Cli, error_chain, execute};
use std::path::Path;

async fn floectl(server: &str, args: &[&str]) -> anyhow::Result<()> {
    let mut argv = vec!["floectl", "--server", server];
    argv.extend_from_slice(args);
    execute(Cli::try_parse_from(argv).expect("valid command line")).await
}

fn text(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Files in `dir`, sorted.
fn files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    v.sort();
    v
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn floectl_drives_a_scene_through_every_command() {
    let server = TestServer::start().await;
    let url = server.grpc_url();
    let dir = tempfile::tempdir().unwrap();
    let mut client = Client::connect(&url).await.unwrap();

    floectl(&url, &["create", "dam_break", "--set", "particle_spacing=0.05"]).await.unwrap();
    let scene = client.list().await.unwrap().pop().expect("one scene");
    assert_eq!((scene.name.as_str(), scene.steps), ("dam_break", 0));
    let (id, n) = (scene.scene_id.to_string(), scene.particles as usize);

    floectl(&url, &["step", &id, "--steps", "5"]).await.unwrap();
    assert_eq!(client.list().await.unwrap()[0].steps, 5);
    floectl(&url, &["set", &id, "gravity=[0,-1,0]"]).await.unwrap();

    let snapshot = dir.path().join("scene.snapshot");
    floectl(&url, &["snapshot", &id, "--out", text(&snapshot)]).await.unwrap();
    floectl(&url, &["step", &id, "--until", "0.02"]).await.unwrap();
    assert!(client.list().await.unwrap()[0].sim_time >= 0.02);
    floectl(&url, &["restore", &id, text(&snapshot)]).await.unwrap();
    assert_eq!(client.list().await.unwrap()[0].steps, 5, "restored to the snapshot's step");

    floectl(&url, &["run", &id]).await.unwrap();
    let recording = dir.path().join("run.floe");
    floectl(&url, &["record", &id, "--out", text(&recording), "--frames", "3", "--fps", "60"]).await.unwrap();
    floectl(&url, &["watch", &id, "--count", "1"]).await.unwrap();
    floectl(&url, &["pause", &id]).await.unwrap();
    assert_eq!(client.list().await.unwrap()[0].state, floe_proto::pb::SceneState::Paused as i32);

    let live = dir.path().join("live");
    floectl(&url, &["export", &id, "--out", text(&live), "--format", "csv"]).await.unwrap();
    let csv = std::fs::read_to_string(&files(&live)[0]).unwrap();
    assert!(csv.starts_with("id,x,y,z,velocity_x,velocity_y,velocity_z,density,pressure\n"), "{}", &csv[..60]);
    assert_eq!(csv.lines().count(), n + 1, "a header and one row per particle");

    floectl(&url, &["delete", &id]).await.unwrap();
    assert!(client.list().await.unwrap().is_empty());
    server.shutdown().await;

    // The recording exports with the server gone.
    let replay = dir.path().join("replay");
    floectl(&url, &["export", "--recording", text(&recording), "--out", text(&replay)]).await.unwrap();
    let exported = files(&replay);
    assert_eq!(exported.len(), 3, "{exported:?}");
    for path in &exported {
        let vtk = std::fs::read(path).unwrap();
        let points = format!("POINTS {n} float");
        assert!(vtk.windows(points.len()).any(|w| w == points.as_bytes()), "{}: no '{points}'", path.display());
    }
}

/// A solid's particles export and record as their own set (`--set solid`), in a series
/// of their own; a set the scene lacks is refused naming those it has.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn floectl_exports_and_records_one_set() {
    let server = TestServer::start().await;
    let url = server.grpc_url();
    let dir = tempfile::tempdir().unwrap();
    floectl(&url, &["create", "floating_blocks", "--set", "particle_spacing=0.04"]).await.unwrap();
    let info = Client::connect(&url).await.unwrap().list().await.unwrap().pop().expect("one scene");
    let id = info.scene_id.to_string();
    let solid = info.sets.iter().find(|s| s.name == "solid").expect("a solid set").count as usize;
    assert!(solid > 0 && solid < info.particles as usize, "{solid} of {}", info.particles);

    let live = dir.path().join("live");
    floectl(&url, &["export", &id, "--set", "solid", "--out", text(&live), "--format", "csv"]).await.unwrap();
    assert_eq!(files(&live), [live.join("solid_00000.csv")]);
    let csv = std::fs::read_to_string(live.join("solid_00000.csv")).unwrap();
    assert!(csv.starts_with("id,x,y,z,velocity_x"), "{}", &csv[..40]);
    assert_eq!(csv.lines().count(), solid + 1, "a header and one row per solid particle");

    let recording = dir.path().join("solid.floe");
    floectl(&url, &["record", &id, "--set", "solid", "--out", text(&recording), "--frames", "1"]).await.unwrap();
    let replay = dir.path().join("replay");
    floectl(&url, &["export", "--recording", text(&recording), "--out", text(&replay)]).await.unwrap();
    let vtk = std::fs::read(&files(&replay)[0]).unwrap();
    let points = format!("POINTS {solid} float");
    assert!(vtk.windows(points.len()).any(|w| w == points.as_bytes()), "no '{points}'");

    let e = error_chain(&floectl(&url, &["export", &id, "--set", "ice", "--out", text(&live)]).await.unwrap_err());
    assert!(e.contains("no set \"ice\"") && e.contains("particles, solid, fluid"), "{e}");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn floectl_errors_name_what_was_wrong() {
    let server = TestServer::start().await;
    let url = server.grpc_url();
    let dir = tempfile::tempdir().unwrap();
    let fails = async |args: &[&str]| error_chain(&floectl(&url, args).await.unwrap_err());

    assert_eq!(fails(&["step", "99"]).await, "no scene with id 99 (NotFound)");
    let e = fails(&["create", "/no/such/scene.toml"]).await;
    assert!(e.starts_with("cannot read /no/such/scene.toml: "), "{e}");
    let e = fails(&["create", "dam_break", "--set", "particle_spacing=-1"]).await;
    assert!(e.contains("particle_spacing") && e.ends_with("(InvalidArgument)"), "{e}");
    // Negative numbers reach the server, which names the field.
    floectl(&url, &["create", "dam_break", "--set", "particle_spacing=0.05"]).await.unwrap();
    let id = server.registry.list(&floe_server::auth::Caller::local())[0].shared.id.to_string();
    let e = fails(&["run", &id, "--rtf", "-2"]).await;
    assert!(e.starts_with("real_time_factor") && e.ends_with("(InvalidArgument)"), "{e}");
    let e = fails(&["step", &id, "--until", "-1"]).await;
    assert!(e.contains("until") && e.ends_with("(InvalidArgument)"), "{e}");
    let garbage = dir.path().join("garbage.floe");
    std::fs::write(&garbage, b"not a recording at all").unwrap();
    let e = fails(&["export", "--recording", text(&garbage), "--out", text(dir.path())]).await;
    assert_eq!(e, "not a Floe recording (no FLOEREC1 header)");

    server.shutdown().await;
    let e = fails(&["list"]).await;
    assert!(e.starts_with(&format!("cannot connect to {url}: ")), "{e}");
    let causes: Vec<&str> = e.split(": ").collect();
    assert!(causes.windows(2).all(|w| w[0] != w[1]), "a cause said twice: {e}");
}
