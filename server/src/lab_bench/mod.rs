//! `floe bench --lab`: a lab server under load. A `floe serve` process (this very
//! binary) with users and tokens; one user's dam break runs as fast as it can (the
//! solver); viewers watch it through read-only share links, some of them never
//! reading their stream; scripted users step, tune and query scenes of their own.
//! Reported: the solver's steps/s alone (before and after the load, so drift from
//! other work on the machine shows) and under load, in the same run; every control
//! call answered or not (lost: no answer within 10 s), errors, frames the viewers
//! read, the CPU the server and the load generator used, and the server's resident
//! memory over the loaded phase.
//!
//! - [`process`]: the server process, its users, its memory.
//! - [`cluster`]: `floe bench --cluster`, a cluster of workers under load through its proxy.
//! - [`step_latency`]: `floe bench --step-latency`, how long a Step call takes to answer.

pub mod cluster;
pub mod process;
pub mod step_latency;

use floe_client::{Client, FrameRequest};
use process::{Data, ServerProcess};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// What to run.
#[derive(Debug, Clone)]
pub struct LoadConfig {
    /// The `floe` binary to serve with.
    pub floe: PathBuf,
    /// `--backend` of the server.
    pub backend: String,
    /// Fluid particles of the solver's dam break (approximate).
    pub particles: usize,
    /// Seconds of the loaded phase (the unloaded one is a quarter of it, 5 to 15 s).
    pub seconds: u64,
    /// Viewers streaming the solver's frames (the idle ones included).
    pub viewers: usize,
    /// Viewers that open their stream and never read it.
    pub idle_viewers: usize,
    /// Scripted users, each with a scene of their own.
    pub scripts: usize,
    /// Calls per second of each scripted user.
    pub script_rate: f64,
}

/// What happened.
#[derive(Debug, Clone, Default)]
pub struct LoadReport {
    /// Fluid particles of the solver's scene.
    pub particles: u64,
    /// The solver's steps/s with nothing else going on: before the load, and after it.
    pub unloaded_steps_per_second: (f64, f64),
    /// The solver's steps/s under load.
    pub loaded_steps_per_second: f64,
    /// Control calls made by the scripted users.
    pub calls: u64,
    /// Calls that got an error.
    pub errors: Vec<String>,
    /// Calls with no answer within 10 s.
    pub lost: u64,
    /// Frames and bytes the reading viewers received.
    pub frames: u64,
    /// Encoded frame bytes the reading viewers received.
    pub frame_bytes: u64,
    /// Viewers whose stream failed or ended early.
    pub viewer_failures: Vec<String>,
    /// Server resident memory once a second through the loaded phase (bytes).
    pub rss: Vec<u64>,
    /// CPU cores the server used: alone before the load, under load, alone after.
    pub server_cores: (f64, f64, f64),
    /// CPU cores the load generator (this process: viewers and scripted users) used.
    pub client_cores: f64,
    /// Whether the server shut down cleanly afterwards.
    pub clean_shutdown: bool,
}

/// A call made by a scripted user waits this long for its answer before it counts as lost.
pub(crate) const CALL_TIMEOUT: Duration = Duration::from_secs(10);

/// Runs the load and stops the server.
pub async fn run(cfg: &LoadConfig) -> anyhow::Result<LoadReport> {
    let dir = tempfile::tempdir()?;
    let data = Data { dir: dir.path().join("data"), database: None };
    let solver_token = process::add_user(&cfg.floe, &data, "solver")?;
    let streams = (cfg.viewers + 4).to_string();
    process::admin(&cfg.floe, &data, &["quota", "set", "solver", &format!("open_streams={streams}")])?;
    let mut script_tokens = Vec::new();
    for k in 0..cfg.scripts {
        script_tokens.push(process::add_user(&cfg.floe, &data, &format!("script{k}"))?);
    }
    let server = ServerProcess::start_empty(&cfg.floe, &data, &cfg.backend, dir.path())?;
    let result = load(cfg, &server, &solver_token, &script_tokens).await;
    let clean_shutdown = server.terminate()?;
    let mut report = result?;
    report.clean_shutdown = clean_shutdown;
    Ok(report)
}

/// CPU time of this process so far (s).
fn own_cpu_seconds() -> f64 {
    process::cpu_seconds("/proc/self/stat").unwrap_or(0.0)
}

/// The solver's steps/s and the server's CPU cores over `seconds` of wall time.
async fn solver_alone(c: &mut Client, id: u64, server: &ServerProcess, seconds: f64) -> anyhow::Result<(f64, f64)> {
    let (s0, cpu0, t0) = (c.stats(id).await?.steps, server.cpu_seconds().unwrap_or(0.0), Instant::now());
    tokio::time::sleep(Duration::from_secs_f64(seconds)).await;
    let wall = t0.elapsed().as_secs_f64();
    let steps = (c.stats(id).await?.steps - s0) as f64 / wall;
    Ok((steps, (server.cpu_seconds().unwrap_or(0.0) - cpu0) / wall))
}

async fn load(
    cfg: &LoadConfig,
    server: &ServerProcess,
    solver_token: &str,
    script_tokens: &[String],
) -> anyhow::Result<LoadReport> {
    let mut solver = Client::connect_with_token(&server.grpc, Some(solver_token)).await?;
    let spacing = crate::bench::spacing_for(cfg.particles);
    let scene = solver.create_preset("dam_break", &[&format!("particle_spacing={spacing}")]).await?;
    let id = scene.scene_id;
    solver.run(id, 0.0).await?;
    let link = solver.share(id).await?.token;
    let mut report = LoadReport { particles: scene.particles, ..LoadReport::default() };
    tokio::time::sleep(Duration::from_secs(3)).await;
    let unloaded_seconds = (cfg.seconds as f64 / 4.0).clamp(5.0, 15.0);
    (report.unloaded_steps_per_second.0, report.server_cores.0) =
        solver_alone(&mut solver, id, server, unloaded_seconds).await?;

    let stop = Arc::new(AtomicBool::new(false));
    let frames = Arc::new((AtomicU64::new(0), AtomicU64::new(0)));
    let mut viewers = Vec::new();
    for k in 0..cfg.viewers {
        let mut c = Client::connect_with_token(&server.grpc, Some(&link)).await?;
        let request = FrameRequest { identity: false, ..FrameRequest::default() };
        let mut stream = c.frames(id, request).await?;
        let (stop, frames) = (stop.clone(), frames.clone());
        let reads = k >= cfg.idle_viewers;
        viewers.push(tokio::spawn(async move {
            if !reads {
                // Holds its stream open and never reads it.
                while !stop.load(Ordering::Relaxed) {
                    tokio::time::sleep(Duration::from_millis(100)).await;
                }
                return Ok::<_, String>(c);
            }
            while !stop.load(Ordering::Relaxed) {
                match stream.next_raw().await {
                    Ok(Some(bytes)) => {
                        frames.0.fetch_add(1, Ordering::Relaxed);
                        frames.1.fetch_add(bytes.len() as u64, Ordering::Relaxed);
                    }
                    Ok(None) => return Err(format!("viewer {k}: the stream ended")),
                    Err(e) => return Err(format!("viewer {k}: {e}")),
                }
            }
            Ok(c)
        }));
    }
    let mut scripts = Vec::new();
    for (k, token) in script_tokens.iter().enumerate() {
        let mut c = Client::connect_with_token(&server.grpc, Some(token)).await?;
        let own = c.create_preset("dam_break", &["particle_spacing=0.05"]).await?.scene_id;
        let (stop, period) = (stop.clone(), Duration::from_secs_f64(1.0 / cfg.script_rate));
        scripts.push(tokio::spawn(async move { script(k, c, own, stop, period).await }));
    }

    // The loaded phase, with the server's memory sampled every second.
    let (t0, cpu0, own0) = (Instant::now(), server.cpu_seconds().unwrap_or(0.0), own_cpu_seconds());
    let s0 = solver.stats(id).await?.steps;
    while t0.elapsed() < Duration::from_secs(cfg.seconds) {
        tokio::time::sleep(Duration::from_secs(1)).await;
        report.rss.extend(server.rss());
    }
    let wall = t0.elapsed().as_secs_f64();
    report.loaded_steps_per_second = (solver.stats(id).await?.steps - s0) as f64 / wall;
    report.server_cores.1 = (server.cpu_seconds().unwrap_or(0.0) - cpu0) / wall;
    report.client_cores = (own_cpu_seconds() - own0) / wall;
    stop.store(true, Ordering::Relaxed);
    for s in scripts {
        let (calls, errors, lost) = s.await?;
        report.calls += calls;
        report.errors.extend(errors);
        report.lost += lost;
    }
    for v in viewers {
        if let Err(e) = v.await? {
            report.viewer_failures.push(e);
        }
    }
    report.frames = frames.0.load(Ordering::Relaxed);
    report.frame_bytes = frames.1.load(Ordering::Relaxed);
    // The viewers' and scripts' connections are closed: the solver alone again.
    tokio::time::sleep(Duration::from_secs(2)).await;
    (report.unloaded_steps_per_second.1, report.server_cores.2) =
        solver_alone(&mut solver, id, server, unloaded_seconds).await?;
    Ok(report)
}

/// A scripted user: every `period`, one call on its own scene (stats, a step, a
/// live setting, the scene list, the scene). Returns calls made, errors, calls lost.
async fn script(k: usize, mut c: Client, own: u64, stop: Arc<AtomicBool>, period: Duration) -> (u64, Vec<String>, u64) {
    let (mut calls, mut errors, mut lost) = (0, Vec::new(), 0);
    while !stop.load(Ordering::Relaxed) {
        let next = Instant::now() + period;
        let gravity = if calls % 2 == 0 { "gravity=[0,-9.81,0]" } else { "gravity=[0,-9.7,0]" };
        let call = async {
            match calls % 5 {
                0 => c.stats(own).await.map(drop),
                1 => c.step(own, 1).await.map(drop),
                2 => c.set_parameters(own, &[gravity]).await.map(drop),
                3 => c.list().await.map(drop),
                _ => c.get(own).await.map(drop),
            }
        };
        match tokio::time::timeout(CALL_TIMEOUT, call).await {
            Ok(Ok(())) => {}
            Ok(Err(e)) => errors.push(format!("script {k}, call {calls}: {e}")),
            Err(_) => lost += 1,
        }
        calls += 1;
        tokio::time::sleep_until(next.into()).await;
    }
    (calls, errors, lost)
}

/// Mean of the first and of the last third of the memory samples.
pub fn rss_thirds(rss: &[u64]) -> Option<(f64, f64)> {
    let third = rss.len() / 3;
    if third == 0 {
        return None;
    }
    let mean = |s: &[u64]| s.iter().sum::<u64>() as f64 / s.len() as f64;
    Some((mean(&rss[..third]), mean(&rss[rss.len() - third..])))
}

/// Prints the report as a table.
pub fn print(cfg: &LoadConfig, r: &LoadReport) {
    let alone = (r.unloaded_steps_per_second.0 + r.unloaded_steps_per_second.1) / 2.0;
    let ratio = r.loaded_steps_per_second / alone.max(f64::MIN_POSITIVE);
    println!(
        "lab load: {} viewers ({} never reading), {} scripted users at {} calls/s each, {} s, solver dam break of {} particles on {}",
        cfg.viewers, cfg.idle_viewers, cfg.scripts, cfg.script_rate, cfg.seconds, r.particles, cfg.backend
    );
    println!("| figure | value |");
    println!("|---|---:|");
    println!("| solver steps/s, alone before the load | {:.1} |", r.unloaded_steps_per_second.0);
    println!("| solver steps/s, under load | {:.1} |", r.loaded_steps_per_second);
    println!("| solver steps/s, alone after the load | {:.1} |", r.unloaded_steps_per_second.1);
    println!("| under load / alone (mean of before and after) | {:.1} % |", 100.0 * ratio);
    let (c, u) = (r.server_cores, r.unloaded_steps_per_second);
    println!("| server CPU cores used: alone before, under load, alone after | {:.2}, {:.2}, {:.2} |", c.0, c.1, c.2);
    // Steps per CPU second the server got: what the load costs the server itself, even
    // when other work on the machine took cores away in some phase.
    let per_core = |steps: f64, cores: f64| steps / cores.max(f64::MIN_POSITIVE);
    println!(
        "| solver steps per server CPU-second: alone before, under load, alone after | {:.1}, {:.1}, {:.1} |",
        per_core(u.0, c.0),
        per_core(r.loaded_steps_per_second, c.1),
        per_core(u.1, c.2)
    );
    println!("| load generator CPU cores used (viewers, scripts) | {:.2} |", r.client_cores);
    println!("| control calls | {} |", r.calls);
    println!("| calls with an error | {} |", r.errors.len());
    println!("| calls lost (no answer in 10 s) | {} |", r.lost);
    let reading = (cfg.viewers - cfg.idle_viewers).max(1) as f64;
    println!("| frames read per reading viewer per s | {:.1} |", r.frames as f64 / reading / cfg.seconds as f64);
    println!("| frame MB/s to all reading viewers | {:.1} |", r.frame_bytes as f64 / 1e6 / cfg.seconds as f64);
    println!("| viewer streams that failed | {} |", r.viewer_failures.len());
    if let (Some((first, last)), Some(max)) = (rss_thirds(&r.rss), r.rss.iter().max()) {
        println!("| server RSS, first third of the load (MiB) | {:.1} |", first / (1 << 20) as f64);
        println!("| server RSS, last third (MiB) | {:.1} |", last / (1 << 20) as f64);
        println!("| server RSS, most (MiB) | {:.1} |", *max as f64 / (1 << 20) as f64);
        let at = |f: f64| r.rss[((r.rss.len() - 1) as f64 * f) as usize] as f64 / (1 << 20) as f64;
        println!(
            "server RSS at 0, 25, 50, 75, 100 % of the load (MiB): {:.1}, {:.1}, {:.1}, {:.1}, {:.1}",
            at(0.0),
            at(0.25),
            at(0.5),
            at(0.75),
            at(1.0)
        );
    }
    println!("| clean shutdown | {} |", if r.clean_shutdown { "yes" } else { "no" });
    if let Ok(load) = std::fs::read_to_string("/proc/loadavg") {
        println!(
            "machine load average at the end (1, 5, 15 min): {}",
            load.split_whitespace().take(3).collect::<Vec<_>>().join(", ")
        );
    }
    for e in r.errors.iter().chain(&r.viewer_failures).take(10) {
        println!("error: {e}");
    }
}
