//! # floe-server
//!
//! The `floe` command: offline runs, benchmarks and the scene schema today; the
//! gRPC/WebSocket simulation server builds on the same engine next.
//!
//! - [`cli`]: the command line (clap).
//! - [`run`]: `floe run`, an offline simulation with progress, exports and a summary.
//! - [`bench`]: `floe bench`, throughput, memory and time to solution.
//! - [`progress`]: the progress display.
//! - [`validate`]: `floe validate`, the validation report and stability battery.

pub mod bench;
pub mod cli;
pub mod progress;
pub mod run;
pub mod validate;

/// Carries out a parsed command line.
pub fn execute(cli: cli::Cli) -> anyhow::Result<()> {
    match cli.command {
        cli::Command::Run(args) => run::run(args),
        cli::Command::Bench(args) => bench::bench(args),
        cli::Command::Validate(args) => validate::validate(args),
        cli::Command::Schema => {
            println!("{}", serde_json::to_string_pretty(&floe_engine::scene::json_schema())?);
            Ok(())
        }
        cli::Command::Presets => {
            for name in floe_engine::scene::presets::NAMES {
                println!("{name}");
            }
            Ok(())
        }
    }
}
