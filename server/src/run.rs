//! `floe run`: simulate a scene offline with progress, exports and a summary.

use crate::cli::{ExportFormat, RunArgs};
use crate::progress::Progress;
use anyhow::{Context, bail};
use floe_engine::Simulation;
use floe_engine::scene::load;
use floe_engine::summary::Summary;
use floe_proto::export::{self, Format};
use std::time::Instant;

/// Runs `args.scene` until `args.until`.
pub fn run(args: RunArgs) -> anyhow::Result<()> {
    if !(args.until.is_finite() && args.until > 0.0) {
        bail!("--until must be a positive number of seconds, got {}", args.until);
    }
    if !(args.every.is_finite() && args.every > 0.0) {
        bail!("--every must be a positive number of seconds, got {}", args.every);
    }
    let scene = load::with_assets(load::resolve(&args.scene, &args.overrides)?, args.assets.as_deref())?;
    let backend = floe_gpu::select::select(args.backend.into())?;
    let mut sim = Simulation::new(scene, &*backend.factory)?;
    tracing::info!(
        scene = %sim.scene().name,
        particles = sim.particle_count(),
        backend = sim.backend_name(),
        "simulating {} s",
        args.until
    );
    let format = match args.format {
        ExportFormat::Vtk => Format::Vtk,
        ExportFormat::Csv => Format::Csv,
    };
    if let Some(dir) = &args.export {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create export directory {}", dir.display()))?;
    }
    let mut frame = 0;
    // Every particle set in a series of its own: the SPH particles' `frame_NNNNN`,
    // another set's (a solid's part of them, snowflakes) named after it. Grids
    // are not exported.
    let mut write_frame = |sim: &Simulation| -> anyhow::Result<()> {
        if let Some(dir) = &args.export {
            for set in sim.model().sets.iter().filter(|s| s.grid.is_none()) {
                let path = dir.join(export::file_name(set.name, frame, format));
                let channels = sim.channels();
                let all: Vec<&str> = channels.iter().filter(|c| c.set == set.channel_set()).map(|c| c.name).collect();
                export::write(&path, format, &sim.read_set(set, &all), sim.time())
                    .with_context(|| format!("cannot write {}", path.display()))?;
            }
            frame += 1;
        }
        Ok(())
    };
    write_frame(&sim)?;
    let mut next_export = args.every;
    let mut progress = Progress::new(args.until, args.quiet);
    let mut stepping = 0.0;
    let mut outcome = Ok(());
    while sim.time() < args.until {
        let t0 = Instant::now();
        let step = sim.step();
        stepping += t0.elapsed().as_secs_f64();
        match step {
            Ok(r) => progress.update(sim.time(), sim.steps(), r.dt, sim.particle_count()),
            Err(h) => {
                outcome = Err(h);
                break;
            }
        }
        if args.export.is_some() && sim.time() >= next_export - 1e-9 {
            write_frame(&sim)?;
            next_export += args.every;
        }
    }
    progress.finish();
    if sim.substeps() > 0 {
        tracing::warn!(
            "the fixed step solver.time_step.dt is above the stable limit: {} sub-steps taken at the limit",
            sim.substeps()
        );
    }
    let summary = Summary::new(&sim, stepping);
    tracing::info!(
        "done: {} steps, {:.2} s wall, {:.2} M particle-steps/s, dt mean {:.2e} s, max density deviation {:.2} %",
        summary.steps,
        summary.wall_seconds,
        summary.particle_steps_per_second / 1e6,
        summary.dt_mean,
        summary.max_density_deviation * 100.0
    );
    // The modules' own measures (the core's are on the line above).
    for m in summary.measures.iter().filter(|m| m.name.contains('.')) {
        tracing::info!("{} = {} {}", m.name, crate::figure::figure(m.value), m.unit);
    }
    if let Some(path) = &args.summary {
        std::fs::write(path, serde_json::to_string_pretty(&summary)? + "\n")
            .with_context(|| format!("cannot write summary {}", path.display()))?;
    }
    outcome.map_err(|h| anyhow::anyhow!("scene '{}' {h}", sim.scene().name))
}
