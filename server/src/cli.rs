//! The command line, defined once with clap.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Floe: particle simulation (SPH fluids) with offline runs and benchmarks.
#[derive(Debug, Parser)]
#[command(name = "floe", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Sub-commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate a scene offline, optionally exporting frames and a summary.
    Run(RunArgs),
    /// Measure fluid particle-steps per second on the dam break.
    Bench(BenchArgs),
    /// Run the simulation server.
    Serve(ServeArgs),
    /// Run the validation cases and the stability battery; write a report.
    Validate(ValidateArgs),
    /// Print a scene's plan: scheme, modules, materials, attributes, passes, channels.
    Plan(PlanArgs),
    /// Print the JSON Schema of scene files.
    Schema,
    /// List the built-in presets.
    Presets,
}

/// Which backend steps the scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// A hardware GPU (Vulkan) when there is one, else the CPU; logs which and why.
    Auto,
    /// A GPU, software adapters (Mesa's lavapipe) included; fails if there is none.
    Gpu,
    /// The rayon CPU backend.
    Cpu,
}

impl From<BackendChoice> for floe_gpu::BackendChoice {
    fn from(c: BackendChoice) -> Self {
        match c {
            BackendChoice::Auto => Self::Auto,
            BackendChoice::Gpu => Self::Gpu,
            BackendChoice::Cpu => Self::Cpu,
        }
    }
}

/// Export file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ExportFormat {
    /// Legacy binary VTK (ParaView).
    Vtk,
    /// CSV with a header row.
    Csv,
}

/// `floe run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// A preset name (`floe presets`) or a scene file (.toml or .json).
    pub scene: String,
    /// Override a scene field, e.g. `--set particle_spacing=0.02` or
    /// `--set fluids[0].viscosity.alpha=0.05` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Simulated time to reach (s).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub until: f64,
    /// Backend.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: BackendChoice,
    /// Write frames into this directory.
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
    /// Simulated seconds between exported frames.
    #[arg(long, value_name = "SECONDS", default_value = "0.02", requires = "export")]
    pub every: f64,
    /// Export format.
    #[arg(long, value_enum, default_value = "vtk", requires = "export")]
    pub format: ExportFormat,
    /// Write a JSON summary of the run here.
    #[arg(long, value_name = "FILE.json")]
    pub summary: Option<PathBuf>,
    /// Never draw the progress bar (it is drawn only on a terminal anyway).
    #[arg(long)]
    pub quiet: bool,
}

/// `floe plan`.
#[derive(Debug, Args)]
pub struct PlanArgs {
    /// A preset name (`floe presets`) or a scene file (.toml or .json).
    pub scene: String,
    /// Override a scene field (repeatable), as in `floe run`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
}

/// `floe bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Fluid particle counts to measure (approximate: the dam break is scaled to them).
    #[arg(long, value_delimiter = ',', default_value = "30000,120000")]
    pub particles: Vec<usize>,
    /// Override a field of the dam break scene (repeatable), as in `floe run`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Steps to time at each size (after warm-up steps).
    #[arg(long, default_value = "100")]
    pub steps: u64,
    /// Backend.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: BackendChoice,
    /// Also report peak resident memory per particle (run one size per process
    /// for a clean figure).
    #[arg(long)]
    pub memory: bool,
    /// GPU backend: also time every kernel with timestamp queries and print
    /// device milliseconds per step for each (adds a wait per submission).
    #[arg(long)]
    pub profile: bool,
    /// Frame codec instead: bytes per particle and encode/decode throughput on
    /// this many dam-break frames at the first particle count.
    #[arg(long, value_name = "FRAMES", conflicts_with = "solve")]
    pub codec: Option<usize>,
    /// Also time each size with the heat module (conduction, buoyancy, a floor held
    /// at 350 K), each size's two rows side by side.
    #[arg(long, conflicts_with_all = ["codec", "solve"])]
    pub heat: bool,
    /// Time to solution instead: simulate this many seconds of the dam break
    /// at the first particle count and report wall time and surge-front error.
    #[arg(long, value_name = "SECONDS")]
    pub solve: Option<f64>,
}

/// `floe validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Coarse resolutions and short stability runs (a few minutes on 2 cores; the default).
    #[arg(long, conflicts_with = "full")]
    pub quick: bool,
    /// Finer resolutions and longer stability runs (the figures kept in docs/validation/).
    #[arg(long)]
    pub full: bool,
    /// Backend.
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendChoice,
    /// Run only these cases (repeatable): a case by name (`floe validate` lists them
    /// when given an unknown one), `stability`, or one stability case by name.
    #[arg(long = "case", value_name = "NAME")]
    pub cases: Vec<String>,
    /// Directory for report.md, report.json and the SVG plots.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// `floe serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// Address for gRPC (loopback unless told otherwise).
    #[arg(long, env = "FLOE_GRPC_ADDR", default_value = "127.0.0.1:50051")]
    pub grpc: String,
    /// Address for HTTP: the viewer, REST and WebSocket (loopback unless told otherwise).
    #[arg(long, env = "FLOE_HTTP_ADDR", default_value = "127.0.0.1:8080")]
    pub http: String,
    /// Directory of the viewer's files (default: `web/` of the source tree).
    #[arg(long, value_name = "DIR")]
    pub web: Option<PathBuf>,
    /// Preset to create at start-up, or `none`.
    #[arg(long, default_value = "dam_break")]
    pub scene: String,
    /// Backend every scene runs on.
    #[arg(long, env = "FLOE_BACKEND", value_enum, default_value = "auto")]
    pub backend: BackendChoice,
    /// Most scenes alive at once, over all users; one more is refused (HTTP 429, gRPC
    /// RESOURCE_EXHAUSTED) until one is deleted.
    #[arg(long, env = "FLOE_MAX_SCENES", default_value_t = crate::service::DEFAULT_MAX_SCENES, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_scenes: u64,
    /// Most fluid particles in one scene; a bigger scene is refused, naming the limit.
    #[arg(long, env = "FLOE_MAX_PARTICLES", default_value_t = crate::service::DEFAULT_MAX_PARTICLES, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_particles: u64,
}

impl ServeArgs {
    /// The registry's limits these flags set.
    pub fn limits(&self) -> crate::service::Limits {
        let size = |v: u64| usize::try_from(v).unwrap_or(usize::MAX);
        crate::service::Limits { max_scenes: size(self.max_scenes), max_particles: size(self.max_particles) }
    }
}
