//! The command line, defined once with clap.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Floe: particle simulation (SPH fluids) with offline runs and benchmarks.
#[derive(Debug, Parser)]
#[command(name = "floe", version, about)]
pub struct Cli {
    /// Log format: `text` for people, `json` (one object per line) for log collectors.
    #[arg(long, global = true, env = "FLOE_LOG_FORMAT", value_enum, default_value = "text")]
    pub log_format: LogFormat,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// How log lines are written (to stderr).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LogFormat {
    /// Human-readable lines (coloured on a terminal).
    Text,
    /// One JSON object per line.
    Json,
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
    /// Manage a lab server's users, tokens and quotas (works beside a running server).
    Admin(crate::admin::AdminArgs),
    /// Run the network- and disk-facing parsers on generated and mutated inputs.
    Fuzz(FuzzArgs),
}

/// `floe fuzz`.
#[derive(Debug, Args)]
pub struct FuzzArgs {
    /// Targets (repeatable; default: all): frame, scene, snapshot, rest, ws.
    #[arg(long = "target", value_enum)]
    pub targets: Vec<crate::fuzz::Target>,
    /// Inputs per target (the seeds included).
    #[arg(long, default_value = "100000")]
    pub inputs: u64,
    /// Seed of the mutations (the same seed tries the same inputs).
    #[arg(long, default_value = "1")]
    pub seed: u64,
    /// Threads (default: one per core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write each input that panics into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Instead of fuzzing, write each target's seeds into DIR/TARGET/ (a starting corpus
    /// for cargo fuzz: `floe fuzz --write-seeds fuzz/corpus`).
    #[arg(long, value_name = "DIR")]
    pub write_seeds: Option<PathBuf>,
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
    /// Directory of the files scenes may name as terrain assets (`heights.asset`); a
    /// scene names only plain file names in it. Without it, scenes naming an asset are refused.
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
}

/// `floe plan`.
#[derive(Debug, Args)]
pub struct PlanArgs {
    /// A preset name (`floe presets`) or a scene file (.toml or .json).
    pub scene: String,
    /// Override a scene field (repeatable), as in `floe run`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Directory of the files scenes may name as terrain assets (`heights.asset`); a
    /// scene names only plain file names in it. Without it, scenes naming an asset are refused.
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
}

/// `floe bench`.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("load").args(["lab", "cluster"])))]
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
    /// Also print milliseconds per step by pass: wall time on the CPU backend, device
    /// time per kernel from timestamp queries on a GPU (adds a wait per submission).
    #[arg(long)]
    pub profile: bool,
    /// A suite instead: `gpu`, every figure tracked on a GPU (the dam break at 1M
    /// particles, the bunny and the ice bunny at full size, the avalanche at 256k, a
    /// million flakes) as a Markdown table; `--backend auto` means the GPU here.
    #[arg(long, value_name = "SUITE", conflicts_with_all = ["codec", "solve", "case"])]
    pub suite: Option<String>,
    /// `--suite`: each figure at a small size (seconds on a software GPU).
    #[arg(long, requires = "suite")]
    pub tiny: bool,
    /// `--suite`: also write the table and the figures as JSON into this directory.
    #[arg(long, value_name = "DIR", requires = "suite")]
    pub out: Option<std::path::PathBuf>,
    /// Frame codec instead: bytes per particle and encode/decode throughput on
    /// this many dam-break frames at the first particle count.
    #[arg(long, value_name = "FRAMES", conflicts_with = "solve")]
    pub codec: Option<usize>,
    /// Views instead: bytes per frame and encode time (with the cull) of a dam break of
    /// the first particle count, whole and through views (a box, a budget, a camera)
    /// holding this share of it (0 to 1, e.g. 0.05).
    #[arg(long, value_name = "SHARE", conflicts_with_all = ["codec", "solve", "case"])]
    pub view: Option<f64>,
    /// A module's benchmark (`floe bench --list` names them): one that runs beside the
    /// dam break times each size twice, side by side; one that runs a preset simulates
    /// it for `--until` seconds at about the first particle count.
    #[arg(long = "case", value_name = "NAME", conflicts_with_all = ["codec", "solve"])]
    pub case: Option<String>,
    /// `--case` of a preset: simulated seconds.
    #[arg(long, value_name = "SECONDS", requires = "case")]
    pub until: Option<f64>,
    /// List the modules' benchmarks.
    #[arg(long)]
    pub list: bool,
    /// Time to solution instead: simulate this many seconds of the dam break
    /// at the first particle count and report wall time and surge-front error.
    #[arg(long, value_name = "SECONDS")]
    pub solve: Option<f64>,
    /// A lab server under load instead: this binary serving with users and tokens, a
    /// dam break of the first particle count running flat out, viewers and scripted
    /// users; the solver's steps/s alone and under load, lost calls, memory.
    #[arg(long, conflicts_with_all = ["codec", "solve"])]
    pub lab: bool,
    /// A cluster under load instead: deploy/local/cluster.sh's three workers (this
    /// binary, CPU backend) behind nginx, three dam breaks at real time, viewers and
    /// scripted users through the proxy; lost calls and the proxy hop's added latency
    /// (each scripted user's reads alternate between the proxy and its scene's worker).
    #[arg(long, conflicts_with_all = ["codec", "solve", "lab"])]
    pub cluster: bool,
    /// Step calls instead: this binary serving (SQLite store) a paused dam break of each
    /// `--particles` count, stepped one step per call `--steps` times; each call's
    /// latency, and a checkpoint's.
    #[arg(long, conflicts_with_all = ["codec", "solve", "lab", "cluster"])]
    pub step_latency: bool,
    /// `--lab`, `--cluster`: seconds under load.
    #[arg(long, default_value = "60", requires = "load")]
    pub seconds: u64,
    /// `--lab`: viewers streaming the running scene through share links; `--cluster`:
    /// viewers streaming the running scenes through the proxy.
    #[arg(long, default_value = "50", requires = "load")]
    pub viewers: usize,
    /// `--lab`: how many of the viewers never read their stream.
    #[arg(long, default_value = "10", requires = "lab")]
    pub idle_viewers: usize,
    /// `--lab`: scripted users, each stepping, tuning and querying a scene of their own;
    /// `--cluster`: each reading a scene of their own.
    #[arg(long, default_value = "10", requires = "load")]
    pub scripts: usize,
    /// `--lab`, `--cluster`: calls per second of each scripted user.
    #[arg(long, default_value = "20", requires = "load")]
    pub script_rate: f64,
}

/// `floe validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Every variant at coarse resolutions and short stability runs (the default):
    /// errors against run time and convergence, bounds checked on the finest run.
    #[arg(long, conflicts_with_all = ["full", "bounds"])]
    pub quick: bool,
    /// Finer resolutions and longer stability runs (the figures kept in docs/validation/).
    #[arg(long, conflicts_with = "bounds")]
    pub full: bool,
    /// Every stated bound, fast: each case's first variant at the one spacing its
    /// bounds are checked at, and the stability battery (what the test suite runs).
    #[arg(long)]
    pub bounds: bool,
    /// Runs at once, each with an equal share of the cores (small scenes step about
    /// as fast on one core as on two, so two at once finish sooner).
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub jobs: usize,
    /// Backend.
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendChoice,
    /// Run only these cases (repeatable): a case by name (`floe validate` lists them
    /// when given an unknown one), `stability`, or one stability case by name.
    #[arg(long = "case", value_name = "NAME")]
    pub cases: Vec<String>,
    /// Override a scene field in every run, before each variant's or stability
    /// case's own overrides (repeatable), e.g. `--set 'solver.method="dfsph"'` to run
    /// the cases on the other scheme (a case that sets the scheme itself keeps it).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Directory for report.md, report.json and the SVG plots.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// Where a server keeps its data (`floe serve`, `floe admin`).
#[derive(Debug, Clone, Args)]
pub struct StoreArgs {
    /// Data directory: the SQLite database and the checkpoints (default
    /// `$XDG_DATA_HOME/floe`, else `~/.local/share/floe`). Global: `floe admin` takes
    /// it before or after its subcommand.
    #[arg(long, env = "FLOE_DATA_DIR", value_name = "DIR", global = true)]
    pub data_dir: Option<PathBuf>,
    /// A PostgreSQL database instead of SQLite, e.g. `postgres://floe@db/floe`
    /// (checkpoints stay in the data directory).
    #[arg(long, env = "FLOE_DATABASE_URL", value_name = "URL", global = true)]
    pub database: Option<String>,
}

impl StoreArgs {
    /// Where the data lives.
    pub fn location(&self) -> crate::store::Location {
        crate::store::Location {
            data_dir: self.data_dir.clone().unwrap_or_else(default_data_dir),
            database: self.database.clone(),
        }
    }
}

/// `$XDG_DATA_HOME/floe`, else `$HOME/.local/share/floe`, else `floe-data` here: a
/// per-user place that outlives the build tree and the working directory.
fn default_data_dir() -> PathBuf {
    let xdg = std::env::var_os("XDG_DATA_HOME").filter(|d| !d.is_empty()).map(PathBuf::from);
    let home = || std::env::var_os("HOME").filter(|d| !d.is_empty()).map(|h| PathBuf::from(h).join(".local/share"));
    xdg.or_else(home).map_or_else(|| PathBuf::from("floe-data"), |d| d.join("floe"))
}

/// How `floe serve` authenticates calls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AuthChoice {
    /// Tokens when the database has users, else single-user (only on loopback addresses).
    Auto,
    /// Every call needs a user's token or a share link.
    Tokens,
    /// No authentication: every call is the `local` admin. Needed explicitly to serve a
    /// non-loopback address without tokens.
    Off,
}

/// A `--quota NAME=VALUE`.
fn quota(text: &str) -> Result<(crate::quota::Limit, u64), String> {
    crate::quota::parse_assignment(text)
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
    /// Scene to create at start-up when the server has none: `auto` (the dam break at
    /// the finest resolution this backend steps at real time or faster, measured at
    /// start), a preset name (`dam_break`: the full 21,952 particles, whatever
    /// `--preset-size` says), or `none`.
    #[arg(long, default_value = "auto")]
    pub scene: String,
    /// Backend every scene runs on.
    #[arg(long, env = "FLOE_BACKEND", value_enum, default_value = "auto")]
    pub backend: BackendChoice,
    /// How a preset created without a `particle_spacing` is sized: `auto` (the
    /// finest spacing this backend steps at real time or faster, measured once per
    /// preset; the scene's info says what was chosen and the full size) or `full`
    /// (the preset's own).
    #[arg(long, env = "FLOE_PRESET_SIZE", value_enum, default_value = "auto")]
    pub preset_size: crate::service::PresetSize,
    /// Most scenes alive at once, over all users; one more is refused (HTTP 429, gRPC
    /// RESOURCE_EXHAUSTED) until one is deleted.
    #[arg(long, env = "FLOE_MAX_SCENES", default_value_t = crate::service::DEFAULT_MAX_SCENES, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_scenes: u64,
    /// Most fluid particles in one scene; a bigger scene is refused, naming the limit.
    #[arg(long, env = "FLOE_MAX_PARTICLES", default_value_t = crate::service::DEFAULT_MAX_PARTICLES, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_particles: u64,
    /// Where scenes, users and checkpoints are kept.
    #[command(flatten)]
    pub store: StoreArgs,
    /// Authentication.
    #[arg(long, env = "FLOE_AUTH", value_enum, default_value = "auto")]
    pub auth: AuthChoice,
    /// A server-wide quota default, e.g. `--quota running_scenes=2` (repeatable):
    /// particles_per_scene, running_scenes, running_particles, open_streams,
    /// requests_per_second. Users' overrides: `floe admin quota set`.
    #[arg(long = "quota", value_name = "NAME=VALUE", value_parser = quota)]
    pub quotas: Vec<(crate::quota::Limit, u64)>,
    /// An origin (`https://dash.example:8443`) besides the server's own whose pages may
    /// open WebSockets (repeatable).
    #[arg(long = "allow-origin", env = "FLOE_ALLOW_ORIGINS", value_delimiter = ',', value_name = "ORIGIN")]
    pub allow_origins: Vec<String>,
    /// Wall seconds a scene runs between periodic checkpoints.
    #[arg(long, env = "FLOE_CHECKPOINT_EVERY", value_name = "SECONDS", default_value_t = crate::service::DEFAULT_CHECKPOINT_SECONDS, value_parser = clap::value_parser!(u64).range(1..))]
    pub checkpoint_every: u64,
    /// Directory of the files scenes may name as terrain assets (`heights.asset`); a
    /// scene names only plain file names in it. Without it, scenes naming an asset are refused.
    #[arg(long, env = "FLOE_ASSETS_DIR", value_name = "DIR")]
    pub assets: Option<PathBuf>,
    /// Joins a cluster as this worker (`floe-0`: lower-case letters, digits, '-'):
    /// every worker names the same PostgreSQL `--database` and the same shared
    /// `--data-dir`, and a proxy in front routes to them (docs/lab-admin.md).
    #[arg(long, env = "FLOE_WORKER", value_name = "NAME", requires = "database")]
    pub worker: Option<String>,
    /// In a cluster, where the others and the proxy reach this worker's gRPC (default: `--grpc`).
    #[arg(long, env = "FLOE_ADVERTISE_GRPC", value_name = "HOST:PORT", requires = "worker")]
    pub advertise_grpc: Option<String>,
    /// In a cluster, where the others and the proxy reach this worker's HTTP (default: `--http`).
    #[arg(long, env = "FLOE_ADVERTISE_HTTP", value_name = "HOST:PORT", requires = "worker")]
    pub advertise_http: Option<String>,
    /// In a cluster, seconds a worker may be silent before the others take its
    /// scenes (from their latest checkpoints); it stops stepping them after half of it.
    #[arg(long, env = "FLOE_LEASE", value_name = "SECONDS", default_value_t = crate::cluster::DEFAULT_LEASE_SECONDS, value_parser = clap::value_parser!(u64).range(2..), requires = "worker")]
    pub lease: u64,
}

impl ServeArgs {
    /// The registry's limits these flags set.
    pub fn limits(&self) -> crate::service::Limits {
        let size = |v: u64| usize::try_from(v).unwrap_or(usize::MAX);
        crate::service::Limits { max_scenes: size(self.max_scenes), max_particles: size(self.max_particles) }
    }

    /// The registry's options these flags set, authenticating in `auth`.
    pub fn options(&self, auth: crate::auth::AuthMode) -> crate::service::Options {
        let mut quotas = crate::quota::QuotaSet::default();
        for &(limit, value) in &self.quotas {
            quotas.set(limit, value);
        }
        crate::service::Options {
            limits: self.limits(),
            quotas,
            auth,
            origins: self.allow_origins.clone(),
            checkpoint_every: std::time::Duration::from_secs(self.checkpoint_every),
            assets: self.assets.clone(),
            preset_size: self.preset_size,
            // `floe serve` sets the backend it chose at start-up.
            ..Default::default()
        }
    }
}
