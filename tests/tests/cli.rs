//! The `floe` command as a user drives it: scene files, presets, overrides,
//! exports, summaries and the errors bad input gets.

use clap::Parser;
use floe_server::cli::Cli;

fn floe(args: &[&str]) -> anyhow::Result<()> {
    let mut argv = vec!["floe"];
    argv.extend_from_slice(args);
    floe_server::execute(Cli::try_parse_from(argv).expect("valid command line"))
}

#[test]
fn a_bad_scene_file_is_rejected_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "particle_spacing = 0.05\n[[fluids]]\nrest_density = -3\nblocks = [{ min = [0,0,0], max = [1,1,1] }]\n",
    )
    .unwrap();
    let err = floe(&["run", path.to_str().unwrap(), "--until", "0.01", "--quiet"]).unwrap_err();
    assert_eq!(format!("{err:#}"), "fluids[0].rest_density: must be > 0, got -3");

    std::fs::write(&path, "particle_spacing = 0.05\nfluids = 3\n").unwrap();
    let err = floe(&["run", path.to_str().unwrap(), "--until", "0.01"]).unwrap_err();
    assert!(format!("{err:#}").starts_with("fluids: invalid type: integer `3`, expected a sequence"), "{err:#}");

    let err = floe(&["run", "no_such_preset", "--until", "0.01"]).unwrap_err();
    assert!(format!("{err:#}").contains("presets are: dam_break, hydrostatic"), "{err:#}");

    let err = floe(&["run", "dam_break", "--until", "-1"]).unwrap_err();
    assert!(format!("{err:#}").contains("--until must be a positive number"), "{err:#}");
}

#[test]
fn run_exports_frames_and_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frames");
    let summary = dir.path().join("summary.json");
    floe(&[
        "run",
        "dam_break",
        "--set",
        "particle_spacing=0.05",
        "--until",
        "0.02",
        "--export",
        out.to_str().unwrap(),
        "--every",
        "0.01",
        "--format",
        "csv",
        "--summary",
        summary.to_str().unwrap(),
        "--quiet",
    ])
    .unwrap();
    let frames: Vec<_> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(frames.len(), 3, "{frames:?}"); // t = 0, 0.01, 0.02
    let csv = std::fs::read_to_string(out.join("frame_00002.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("id,x,y,z,velocity_x,velocity_y,velocity_z,density,pressure"));
    assert_eq!(lines.count(), 1000); // 10 x 20 x 5 particles at a/10
    let s: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    assert_eq!(s["particles"], 1000);
    assert!(s["simulated_seconds"].as_f64().unwrap() >= 0.02);
    for key in ["steps", "wall_seconds", "particle_steps_per_second", "dt_min", "dt_mean", "dt_max"] {
        assert!(s[key].as_f64().unwrap() > 0.0, "{key}: {}", s[key]);
    }
    assert!(s["max_density_deviation"].as_f64().is_some() && s["mean_density_deviation"].as_f64().is_some());
    assert!(s["halted"].is_null());
}

/// A scene with a solid exports its particles and each of their parts, one file per
/// set and frame, ids the particles': the solid's and the fluid's rows split the
/// particles' rows.
#[test]
fn run_exports_one_file_per_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frames");
    let args = ["run", "ice_melting", "--set", "particle_spacing=0.02", "--until", "0.01", "--format", "csv"];
    floe(&[&args[..], &["--export", out.to_str().unwrap(), "--every", "0.01", "--quiet"]].concat()).unwrap();
    let mut files: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    files.sort();
    assert_eq!(files[..3], ["fluid_00000.csv", "fluid_00001.csv", "frame_00000.csv"], "{files:?}");
    assert_eq!(files.len(), 6, "{files:?}");
    let rows = |name: &str| -> Vec<(u32, String)> {
        let csv = std::fs::read_to_string(out.join(name)).unwrap();
        let mut lines = csv.lines();
        assert!(lines.next().unwrap().starts_with("id,x,y,z,velocity_x"), "{name}");
        lines.map(|l| (l.split(',').next().unwrap().parse().unwrap(), l.to_string())).collect()
    };
    let mut parts = [rows("solid_00001.csv"), rows("fluid_00001.csv")].concat();
    assert!(parts.len() > 1000, "{} rows", parts.len());
    parts.sort_by_key(|(id, _)| *id);
    assert_eq!(parts, rows("frame_00001.csv"));
}

#[test]
fn a_dfsph_run_summary_lists_its_solves() {
    let dir = tempfile::tempdir().unwrap();
    let summary = dir.path().join("summary.json");
    let args = ["run", "dam_break", "--set", "particle_spacing=0.05", "--set", "solver.method=\"dfsph\""];
    floe(&[&args[..], &["--until", "0.02", "--summary", summary.to_str().unwrap(), "--quiet"]].concat()).unwrap();
    let s: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    for solve in ["dfsph.divergence", "dfsph.density"] {
        let stats = &s["solves"][solve];
        assert!(stats["total_iterations"].as_u64().unwrap() >= s["steps"].as_u64().unwrap(), "{solve}: {stats}");
        assert!(stats["max_iterations"].as_u64().unwrap() >= 1, "{solve}: {stats}");
    }
}

#[test]
fn a_halted_run_reports_why_and_still_writes_its_summary() {
    let dir = tempfile::tempdir().unwrap();
    let summary = dir.path().join("summary.json");
    let err = floe(&[
        "run",
        "dam_break",
        "--set",
        "particle_spacing=0.05",
        "--set",
        "solver.speed_of_sound=0.5",
        "--until",
        "1",
        "--summary",
        summary.to_str().unwrap(),
        "--quiet",
    ])
    .unwrap_err();
    let msg = format!("{err:#}");
    assert!(msg.starts_with("scene 'dam_break' halted at step"), "{msg}");
    let s: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    assert!(s["halted"].as_str().unwrap().contains("exceeds guard."), "{}", s["halted"]);
}

#[test]
fn the_schema_describes_scene_files() {
    let schema = floe_engine::scene::json_schema();
    assert_eq!(schema["title"], "Scene");
    assert!(schema["required"].as_array().unwrap().iter().any(|r| r == "particle_spacing"));
    assert!(schema["properties"]["fluids"].is_object());
    // Tunable fields are marked with their unit and bounds, the module's through its
    // definition (fluids[*] is a reference to Fluid).
    assert_eq!(schema["properties"]["gravity"]["x-floe-tunable"]["unit"], "m/s^2");
    let xsph = &schema["$defs"]["Fluid"]["properties"]["xsph"]["x-floe-tunable"];
    assert_eq!(
        (xsph["min"].as_f64(), xsph["max"].as_f64(), xsph["module"].as_str()),
        (Some(0.0), Some(1.0), Some("fluid"))
    );
    let damping = &schema["$defs"]["Solver"]["properties"]["damping"]["x-floe-tunable"];
    assert_eq!(damping["unit"], "1/s");
    assert!(schema["properties"]["particle_spacing"].get("x-floe-tunable").is_none());
    floe(&["schema"]).unwrap();
}

#[test]
fn the_example_scenes_run() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let mut ran = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        floe(&["run", path.to_str().unwrap(), "--until", "0.01", "--quiet"])
            .unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
        ran += 1;
    }
    assert!(ran > 0, "no example scenes in {}", dir.display());
}

/// `floe admin` takes `--data-dir` and `--database` before or after its subcommand,
/// the order people type them in.
#[test]
fn admin_store_options_go_before_or_after_the_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().to_str().unwrap();
    floe(&["admin", "user", "add", "ada", "--data-dir", data]).unwrap();
    floe(&["admin", "--data-dir", data, "user", "add", "bob", "--admin"]).unwrap();
    floe(&["admin", "quota", "set", "ada", "running_scenes=2", "--data-dir", data]).unwrap();
    let err = floe(&["admin", "user", "add", "ada", "--data-dir", data]).unwrap_err();
    assert!(format!("{err:#}").contains("ada"), "the second ada is refused in the same directory: {err:#}");
    let users = tokio::runtime::Runtime::new().unwrap().block_on(async {
        let location = floe_server::store::Location { data_dir: dir.path().into(), database: None };
        let db = location.open_database().await.unwrap();
        let users = db.users().await.unwrap();
        db.close().await;
        users
    });
    let names: Vec<(&str, bool)> = users.iter().map(|u| (u.name.as_str(), u.admin)).collect();
    assert_eq!(names, [("ada", false), ("bob", true)]);
    // --database after the subcommand is taken as well (here a server that is not
    // there: the error names it, which only a parsed option can).
    let err = floe(&["admin", "user", "list", "--database", "postgres://floe@127.0.0.1:1/none"]).unwrap_err();
    assert!(format!("{err:#}").contains("127.0.0.1:1"), "{err:#}");
}

/// `floe bench --case` takes the modules' benchmarks by name: a module's preset
/// runs for the simulated time asked for; a wrong name or a missing time is named.
#[test]
fn bench_cases_come_from_the_modules() {
    let names: Vec<&str> = floe_engine::module::bench_cases().iter().map(|c| c.name).collect();
    assert_eq!(names, ["heat", "avalanche", "snowfall", "solid", "bunny", "ice"]);
    let err = floe(&["bench", "--case", "nope"]).unwrap_err();
    assert_eq!(
        format!("{err:#}"),
        "no bench case nope; there are [\"heat\", \"avalanche\", \"snowfall\", \"solid\", \"bunny\", \"ice\"]"
    );
    let err = floe(&["bench", "--backend", "cpu", "--case", "avalanche"]).unwrap_err();
    assert_eq!(format!("{err:#}"), "--case of a preset needs --until SECONDS (simulated time)");
    floe(&["bench", "--backend", "cpu", "--case", "avalanche", "--until", "0.001", "--particles", "2000"]).unwrap();
    floe(&["bench", "--backend", "cpu", "--case", "heat", "--particles", "2000", "--steps", "2"]).unwrap();
    floe(&["bench", "--backend", "cpu", "--case", "snowfall", "--until", "0.3", "--particles", "2000"]).unwrap();
}
