//! `floe bench --step-latency`: how long a script waits for a Step call. A `floe
//! serve` process (this very binary, keeping its scenes in a fresh SQLite data
//! directory) holds a paused dam break of each particle count; one client steps it
//! one step per call, back to back, then asks for checkpoints by hand. Reported per
//! size: the Step call's latency (median, 95th percentile, mean) and a checkpoint's
//! (median): what making every answered step durable costs a stepping script.

use super::cluster::percentile_ms;
use super::process::{Data, ServerProcess};
use floe_client::Client;
use std::path::PathBuf;
use std::time::Instant;

/// What to run.
#[derive(Debug, Clone)]
pub struct StepLatency {
    /// The `floe` binary to serve with.
    pub floe: PathBuf,
    /// `--backend` of the server.
    pub backend: String,
    /// Fluid particle counts of the dam breaks (approximate).
    pub particles: Vec<usize>,
    /// Step calls timed per size (after ten untimed ones).
    pub calls: u64,
}

/// One size's figures: latencies in seconds.
#[derive(Debug, Clone)]
pub struct Row {
    /// Fluid particles of the scene.
    pub particles: u64,
    /// Each Step call's latency, one step per call.
    pub step: Vec<f64>,
    /// Each Checkpoint call's latency.
    pub checkpoint: Vec<f64>,
}

/// Runs every size on one server and stops it.
pub async fn run(cfg: &StepLatency) -> anyhow::Result<Vec<Row>> {
    let dir = tempfile::tempdir()?;
    let data = Data { dir: dir.path().join("data"), database: None };
    let server = ServerProcess::start_empty(&cfg.floe, &data, &cfg.backend, dir.path())?;
    let mut c = Client::connect(&server.grpc).await?;
    let mut rows = Vec::new();
    for &particles in &cfg.particles {
        let spacing = crate::bench::spacing_for(particles);
        let scene = c.create_preset("dam_break", &[&format!("particle_spacing={spacing}")]).await?;
        let id = scene.scene_id;
        c.step(id, 10).await?;
        let mut row = Row { particles: scene.particles, step: Vec::new(), checkpoint: Vec::new() };
        for _ in 0..cfg.calls {
            let t0 = Instant::now();
            c.step(id, 1).await?;
            row.step.push(t0.elapsed().as_secs_f64());
        }
        for _ in 0..cfg.calls.clamp(1, 20) {
            let t0 = Instant::now();
            c.checkpoint(id).await?;
            row.checkpoint.push(t0.elapsed().as_secs_f64());
        }
        c.delete(id).await?;
        rows.push(row);
    }
    server.terminate()?;
    Ok(rows)
}

/// Prints the figures as a table.
pub fn print(cfg: &StepLatency, rows: &[Row]) {
    println!(
        "Step calls of one step each, back to back, on a paused dam break ({} backend, SQLite store):",
        cfg.backend
    );
    println!("| particles | Step calls | Step median (ms) | Step p95 (ms) | Step mean (ms) | checkpoint median (ms) |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let mean = 1e3 * r.step.iter().sum::<f64>() / r.step.len().max(1) as f64;
        println!(
            "| {} | {} | {:.2} | {:.2} | {mean:.2} | {:.2} |",
            r.particles,
            r.step.len(),
            percentile_ms(&r.step, 0.5),
            percentile_ms(&r.step, 0.95),
            percentile_ms(&r.checkpoint, 0.5)
        );
    }
}
