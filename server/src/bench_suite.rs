//! `floe bench --suite gpu`: every figure the project tracks on a GPU, in one
//! command (under 8 minutes on one data-centre GPU): the dam break's particle-steps
//! per second at a million particles, the bunny and the melting ice bunny at their
//! full size (real-time factor), the avalanche at 256k particles and a million
//! snowflakes. It prints a Markdown table (with `--profile`, each figure's time per
//! pass after it) and, with `--out DIR`, writes it and the figures as JSON there.
//! `--tiny` runs each at a small size, fast on a software GPU: the test suite does,
//! on lavapipe, so the suite never rots.

use crate::bench::{PresetFigures, PresetRun, dam_break, find_case, measure_preset, per_step};
use anyhow::Context;
use floe_engine::module::BenchKind;
use floe_gpu::Selected;
use std::fmt::Write as _;
use std::time::Instant;

/// What a figure measures.
#[derive(Debug, Clone, Copy)]
enum Measure {
    /// The dam break scaled to about `particles`, `steps` steps timed after 5 of warm-up.
    DamBreak { particles: usize, steps: u64 },
    /// A module's benchmark case (`floe bench --list`) at about `count` of what it
    /// counts, simulated for `seconds`.
    Case { case: &'static str, count: usize, seconds: f64 },
}

/// A figure of the suite: its full size and its tiny one.
#[derive(Debug)]
struct Item {
    name: &'static str,
    what: &'static str,
    full: Measure,
    tiny: Measure,
}

/// The GPU suite.
const GPU: &[Item] = &[
    Item {
        name: "dam_break",
        what: "the dam break (M steps/s: particle-steps per second)",
        full: Measure::DamBreak { particles: 1_000_000, steps: 20 },
        tiny: Measure::DamBreak { particles: 8_000, steps: 3 },
    },
    Item {
        name: "bunny",
        what: "the elastic bunny dropped on the floor",
        full: Measure::Case { case: "bunny", count: 6_537, seconds: 0.5 },
        tiny: Measure::Case { case: "bunny", count: 300, seconds: 0.02 },
    },
    Item {
        name: "ice_melting",
        what: "the ice bunny melting in water",
        full: Measure::Case { case: "ice", count: 17_037, seconds: 0.5 },
        tiny: Measure::Case { case: "ice", count: 1_200, seconds: 0.02 },
    },
    Item {
        name: "avalanche",
        what: "the avalanche",
        full: Measure::Case { case: "avalanche", count: 256_000, seconds: 0.05 },
        tiny: Measure::Case { case: "avalanche", count: 2_000, seconds: 0.01 },
    },
    Item {
        name: "flakes",
        what: "snowflakes in the air",
        full: Measure::Case { case: "snowfall", count: 1_000_000, seconds: 1.0 },
        tiny: Measure::Case { case: "snowfall", count: 5_000, seconds: 0.2 },
    },
];

/// One figure measured.
#[derive(Debug, serde::Serialize)]
struct Row {
    name: &'static str,
    what: &'static str,
    /// What was counted and how many.
    counted: &'static str,
    count: usize,
    simulated: f64,
    steps: u64,
    dt_mean: f64,
    wall: f64,
    /// Simulated seconds per wall second (none for the dam break's fixed steps).
    real_time_factor: Option<f64>,
    /// Millions of counted element-steps per wall second.
    m_steps_per_second: f64,
    /// Time per step by pass (pass, ms per step, calls per step), slowest first,
    /// where the backend timed them (`--profile` on a GPU).
    passes: Vec<(&'static str, f64, f64)>,
}

/// The suite's report.
#[derive(Debug, serde::Serialize)]
struct Report {
    suite: &'static str,
    device: String,
    tiny: bool,
    profiled: bool,
    date: String,
    rows: Vec<Row>,
}

/// Runs suite `name` (`gpu`) on `backend`.
pub fn run(
    name: &str,
    tiny: bool,
    profile: bool,
    backend: &Selected,
    out: Option<&std::path::Path>,
) -> anyhow::Result<()> {
    anyhow::ensure!(name == "gpu", "--suite: the suite is \"gpu\", got {name:?}");
    let mut rows = Vec::new();
    for item in GPU {
        let m = if tiny { item.tiny } else { item.full };
        let t0 = Instant::now();
        let row = measure(item, m, backend).with_context(|| format!("suite figure {}", item.name))?;
        tracing::info!("{}: {:.1} s", item.name, t0.elapsed().as_secs_f64());
        rows.push(row);
    }
    let report = Report {
        suite: "gpu",
        device: backend.description.clone(),
        tiny,
        profiled: profile,
        date: crate::validate::report::today(),
        rows,
    };
    let text = markdown(&report);
    print!("{text}");
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        std::fs::write(dir.join("gpu-suite.md"), &text)?;
        std::fs::write(dir.join("gpu-suite.json"), serde_json::to_string_pretty(&report)? + "\n")?;
    }
    Ok(())
}

fn measure(item: &Item, m: Measure, backend: &Selected) -> anyhow::Result<Row> {
    match m {
        Measure::DamBreak { particles, steps } => {
            let mut sim = dam_break(particles, &[], backend)?;
            for _ in 0..5 {
                sim.step().context("warm-up")?;
            }
            let (before, t0, s0, time0) = (sim.kernel_times(), Instant::now(), sim.steps(), sim.time());
            for _ in 0..steps {
                sim.step().context("timed step")?;
            }
            let wall = t0.elapsed().as_secs_f64();
            let n = sim.particle_count();
            Ok(Row {
                name: item.name,
                what: item.what,
                counted: "particles",
                count: n,
                simulated: sim.time() - time0,
                steps: sim.steps() - s0,
                dt_mean: (sim.time() - time0) / steps as f64,
                wall,
                real_time_factor: None,
                m_steps_per_second: n as f64 * steps as f64 / wall / 1e6,
                passes: per_step(&before, &sim.kernel_times(), steps),
            })
        }
        Measure::Case { case, count, seconds } => {
            let BenchKind::Run { preset, measures, size } = find_case(case)?.kind else {
                anyhow::bail!("bench case {case} does not run a preset")
            };
            let run = PresetRun { preset, measures, size, count, seconds, memory: false };
            let f: PresetFigures = measure_preset(&run, &[], backend)?;
            Ok(Row {
                name: item.name,
                what: item.what,
                counted: f.counted,
                count: f.count,
                simulated: f.simulated,
                steps: f.steps,
                dt_mean: f.dt_mean,
                wall: f.wall,
                real_time_factor: Some(f.real_time_factor()),
                m_steps_per_second: f.m_steps_per_second(),
                passes: f.passes,
            })
        }
    }
}

fn markdown(r: &Report) -> String {
    let mut s = String::new();
    let size = if r.tiny { "tiny sizes" } else { "full sizes" };
    let _ =
        writeln!(s, "GPU suite ({size}) on {}, {}{}\n", r.device, r.date, if r.profiled { ", profiled" } else { "" });
    let _ = writeln!(
        s,
        "| figure | what | counted | simulated s | steps | dt mean s | wall s | real-time factor | M steps/s |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for row in &r.rows {
        let rtf = row.real_time_factor.map_or("-".into(), |f| format!("{f:.3}"));
        let _ = writeln!(
            s,
            "| {} | {} | {} {} | {:.3} | {} | {:.2e} | {:.2} | {rtf} | {:.2} |",
            row.name,
            row.what,
            row.count,
            row.counted,
            row.simulated,
            row.steps,
            row.dt_mean,
            row.wall,
            row.m_steps_per_second
        );
    }
    // With `--profile`: the slowest passes of each figure, per step.
    for row in r.rows.iter().filter(|r| r.profiled_passes()) {
        let total: f64 = row.passes.iter().map(|p| p.1).sum();
        let _ = writeln!(
            s,
            "\n{} ({} {}): {total:.3} ms a step by pass, the slowest ten\n",
            row.name, row.count, row.counted
        );
        let _ = writeln!(s, "| pass | calls/step | ms/step | share |\n|---|---:|---:|---:|");
        for (pass, ms, calls) in row.passes.iter().take(10) {
            let _ =
                writeln!(s, "| {pass} | {calls:.1} | {ms:.3} | {:.1} % |", 100.0 * ms / total.max(f64::MIN_POSITIVE));
        }
    }
    s
}

impl Row {
    /// Whether the backend timed this figure's passes (`--profile` on a GPU, always on the CPU).
    fn profiled_passes(&self) -> bool {
        !self.passes.is_empty()
    }
}
