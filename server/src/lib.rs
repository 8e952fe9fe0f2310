//! # floe-server
//!
//! The `floe` command: the simulation server (`floe serve`, gRPC), offline runs,
//! benchmarks, validation and the scene schema.
//!
//! - [`entry`]: the command's entry point (a binary that compiles in more modules
//!   registers them and calls it).
//! - [`cli`]: the command line (clap).
//! - [`run`]: `floe run`, an offline simulation with progress, exports and a summary.
//! - [`bench`]: `floe bench`, throughput, memory and time to solution.
//! - [`codec_bench`]: `floe bench --codec`, frame size and codec throughput.
//! - [`plan`]: `floe plan`, what a scene allocates and runs.
//! - [`progress`]: the progress display.
//! - [`validate`]: `floe validate`, the validation report and stability battery.
//! - [`serve`]: `floe serve`, the server: listeners, health, reflection, shutdown;
//!   [`sizing`]: presets (and the default scene) sized to the backend.
//! - [`service`]: the in-process service API (scenes, workers, frame subscriptions).
//! - [`grpc`], [`convert`]: the gRPC adapter and where generated types meet the service.
//! - [`http`], [`ws`]: the viewer's files, the REST mirror and the per-scene WebSocket.
//! - [`auth`]: users, tokens, share links and single-user mode; [`grpc_guard`] and
//!   `http::guard` apply them (with the request rate and the metrics) to every call.
//! - [`grpc_lab`]: `floe.v1.LabService` (checkpoints, share links, users, quotas).
//! - [`quota`]: per-user quotas. [`metrics`]: Prometheus metrics.
//! - [`store`]: the database and checkpoint files. [`admin`]: `floe admin`.
//! - [`cluster`]: several workers sharing one database behind one proxy: placement,
//!   heartbeats, leases and fencing.
//! - [`echo`]: error messages bounded however large the request.
//! - [`lab_bench`]: `floe bench --lab`, a lab server under load.
//! - [`fuzz`]: `floe fuzz`, the parsers on generated and mutated inputs.

pub mod admin;
pub mod auth;
pub mod bench;
pub mod bench_suite;
pub mod cli;
pub mod cluster;
pub mod codec_bench;
pub mod convert;
pub mod echo;
pub mod entry;
pub mod figure;
pub mod fuzz;
pub mod grpc;
pub mod grpc_guard;
pub mod grpc_lab;
pub mod http;
pub mod lab_bench;
pub mod metrics;
pub mod plan;
pub mod progress;
pub mod quota;
pub mod run;
pub mod serve;
pub mod service;
pub mod sizing;
pub mod store;
pub mod validate;
pub mod ws;

/// Carries out a parsed command line.
pub fn execute(cli: cli::Cli) -> anyhow::Result<()> {
    match cli.command {
        cli::Command::Run(args) => run::run(args),
        cli::Command::Bench(args) => bench::bench(args),
        cli::Command::Validate(args) => validate::validate(args),
        cli::Command::Serve(args) => serve::serve(args),
        cli::Command::Plan(args) => {
            print!("{}", plan::describe(&args.scene, &args.overrides, args.assets.as_deref())?);
            Ok(())
        }
        cli::Command::Schema => {
            println!("{}", serde_json::to_string_pretty(&floe_engine::scene::json_schema())?);
            Ok(())
        }
        cli::Command::Admin(args) => admin::admin(args),
        cli::Command::Fuzz(args) => fuzz::command(args),
        cli::Command::Presets => {
            for p in floe_engine::module::presets() {
                println!("{:<14} {}", p.name, p.about);
            }
            Ok(())
        }
    }
}
