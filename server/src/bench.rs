//! `floe bench`: fluid particle-steps per second on the dam break, peak memory,
//! time to solution with the surge-front error, the modules' benchmarks (`--case`:
//! the dam break with a module beside it, or a module's preset run for a time),
//! (`--codec`) the frame codec, and (`--suite gpu`, [`crate::bench_suite`]) every
//! figure tracked on a GPU.

use crate::cli::BenchArgs;
use anyhow::Context;
use floe_engine::Simulation;
use floe_engine::module::{BenchCase, BenchKind, BenchSize};
use floe_engine::modules::fluid::presets::DAM_BREAK_A;
use floe_engine::scene::load;
use floe_engine::validation::dam_break;
use floe_gpu::Selected;
use std::time::Instant;

/// The particle spacing that scales the dam break to about `particles` fluid
/// particles (the column holds n^3 particles for spacing a/n).
pub fn spacing_for(particles: usize) -> f32 {
    DAM_BREAK_A / (particles as f32).cbrt().round()
}

/// The dam break scaled to about `particles` fluid particles.
pub(crate) fn dam_break(particles: usize, overrides: &[String], backend: &Selected) -> anyhow::Result<Simulation> {
    let spacing = format!("particle_spacing={}", spacing_for(particles));
    let all: Vec<String> = std::iter::once(spacing).chain(overrides.iter().cloned()).collect();
    Ok(Simulation::new(load::from_preset("dam_break", &all)?, &*backend.factory)?)
}

/// Peak resident set size of this process (bytes), from /proc.
fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse::<u64>().ok().map(|kb| kb * 1024)
}

/// Runs the benchmark and prints a table.
pub fn bench(args: BenchArgs) -> anyhow::Result<()> {
    if args.lab {
        return lab(&args);
    }
    if args.cluster {
        return cluster(&args);
    }
    if args.step_latency {
        return step_latency(&args);
    }
    if args.list {
        println!("| case | module benchmark |\n|---|---|");
        for c in floe_engine::module::bench_cases() {
            println!("| {} | {} |", c.name, c.about);
        }
        return Ok(());
    }
    if let Some(share) = args.view {
        return crate::codec_bench::view_bench(args.particles[0], share);
    }
    if let Some(frames) = args.codec {
        return crate::codec_bench::codec_bench(args.particles[0], frames);
    }
    if let Some(suite) = &args.suite {
        // The suite is the GPU's: `auto` means the GPU, software adapters included.
        let choice = match args.backend {
            crate::cli::BackendChoice::Auto => crate::cli::BackendChoice::Gpu,
            other => other,
        };
        let backend = floe_gpu::select::select_with(choice.into(), args.profile)?;
        return crate::bench_suite::run(suite, args.tiny, args.profile, &backend, args.out.as_deref());
    }
    let case = args.case.as_deref().map(find_case).transpose()?;
    let backend = floe_gpu::select::select_with(args.backend.into(), args.profile)?;
    if let Some(seconds) = args.solve {
        return solve(args.particles[0], &args.overrides, seconds, &backend);
    }
    let mut beside = args.overrides.clone();
    match case.map(|c| c.kind) {
        Some(BenchKind::Run { preset, measures, size }) => {
            let seconds = args.until.context("--case of a preset needs --until SECONDS (simulated time)")?;
            let run = PresetRun { preset, measures, size, count: args.particles[0], seconds, memory: args.memory };
            return run_preset(&run, &args.overrides, &backend, args.profile);
        }
        Some(BenchKind::Beside(overrides)) => beside.extend(overrides.iter().map(|s| s.to_string())),
        None => {}
    }
    let scheme = floe_engine::scheme::of(&load::from_preset("dam_break", &args.overrides)?).id;
    println!("dam break ({scheme}) on {}, {} timed steps per size", backend.description, args.steps);
    println!(
        "| modules | fluid particles | steps | wall s | ms/step | M particle-steps/s | peak RSS bytes/particle | device bytes/particle | solver iterations/step |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut variants = vec![("fluid".to_string(), &args.overrides)];
    if let Some(c) = case {
        variants.push((format!("fluid, {}", c.name), &beside));
    }
    let mut profiles = Vec::new();
    for (&n, (modules, overrides)) in args.particles.iter().flat_map(|n| variants.iter().map(move |v| (n, v))) {
        let mut sim = dam_break(n, overrides, &backend)?;
        for _ in 0..5 {
            sim.step().context("warm-up")?;
        }
        let kernels_before = sim.kernel_times();
        let iterations_before = iterations(&sim);
        let t0 = Instant::now();
        for _ in 0..args.steps {
            sim.step().context("timed step")?;
        }
        let wall = t0.elapsed().as_secs_f64();
        let label = format!("{} particles ({modules})", sim.particle_count());
        profiles.push((label, per_step(&kernels_before, &sim.kernel_times(), args.steps)));
        let p = sim.particle_count();
        let per_particle = |b: u64| format!("{:.0}", b as f64 / p as f64);
        let mem = if args.memory { peak_rss().map(per_particle) } else { None };
        let device = sim.device_memory().map(per_particle);
        let solved = iterations(&sim) - iterations_before;
        println!(
            "| {modules} | {p} | {} | {wall:.2} | {:.2} | {:.2} | {} | {} | {} |",
            args.steps,
            wall * 1e3 / args.steps as f64,
            p as f64 * args.steps as f64 / wall / 1e6,
            mem.unwrap_or_else(|| "-".into()),
            device.unwrap_or_else(|| "-".into()),
            per_step_iterations(&sim, solved, args.steps)
        );
    }
    for (label, kernels) in profiles.iter().filter(|k| args.profile && !k.1.is_empty()) {
        print_profile(label, kernels, backend.name);
    }
    Ok(())
}

/// The table of time per step by pass.
pub(crate) fn print_profile(label: &str, kernels: &[(&'static str, f64, f64)], backend: &str) {
    let total: f64 = kernels.iter().map(|k| k.1).sum();
    let how = if backend == "cpu" { "CPU wall time" } else { "GPU timestamp queries" };
    println!("\nTime per step by pass at {label} ({how}), {total:.3} ms in all:");
    println!("| pass | calls/step | ms/step | share |");
    println!("|---|---:|---:|---:|");
    for (label, ms, dispatches) in kernels.iter() {
        println!("| {label} | {dispatches:.1} | {ms:.3} | {:.1} % |", 100.0 * ms / total.max(f64::MIN_POSITIVE));
    }
}

/// The module benchmark called `name`.
pub(crate) fn find_case(name: &str) -> anyhow::Result<BenchCase> {
    let cases = floe_engine::module::bench_cases();
    let names: Vec<&str> = cases.iter().map(|c| c.name).collect();
    cases.iter().copied().find(|c| c.name == name).with_context(|| format!("no bench case {name}; there are {names:?}"))
}

/// A module's preset run: which, what to report, how big and how long.
pub(crate) struct PresetRun {
    pub(crate) preset: &'static str,
    pub(crate) measures: &'static [&'static str],
    pub(crate) size: BenchSize,
    /// About how many particles (or elements of the sized space).
    pub(crate) count: usize,
    /// Simulated time (s).
    pub(crate) seconds: f64,
    /// Whether to report the peak resident memory per element.
    pub(crate) memory: bool,
}

/// What a preset run measured.
#[derive(Debug, serde::Serialize)]
pub(crate) struct PresetFigures {
    /// The preset.
    pub(crate) preset: &'static str,
    /// The overrides that sized it.
    pub(crate) sizing: Vec<String>,
    /// What was counted (`particles`, or a module's space).
    pub(crate) counted: &'static str,
    /// How many.
    pub(crate) count: usize,
    /// Simulated seconds.
    pub(crate) simulated: f64,
    /// Steps.
    pub(crate) steps: u64,
    /// Mean dt (s).
    pub(crate) dt_mean: f64,
    /// Solver iterations per step ("-" for a scheme without solves).
    pub(crate) iterations: String,
    /// Wall seconds stepping.
    pub(crate) wall: f64,
    /// Peak resident memory per counted element (bytes), where asked for.
    pub(crate) memory: Option<f64>,
    /// The preset's measures asked for: (name, value, unit).
    pub(crate) measures: Vec<(String, f64, String)>,
    /// Time per step by pass: (pass, ms per step, calls per step), slowest first.
    pub(crate) passes: Vec<(&'static str, f64, f64)>,
}

impl PresetFigures {
    /// Milliseconds per step.
    pub(crate) fn ms_per_step(&self) -> f64 {
        self.wall * 1e3 / self.steps.max(1) as f64
    }

    /// Millions of element-steps per wall second.
    pub(crate) fn m_steps_per_second(&self) -> f64 {
        self.count as f64 * self.steps as f64 / self.wall / 1e6
    }

    /// Simulated seconds per wall second.
    pub(crate) fn real_time_factor(&self) -> f64 {
        self.simulated / self.wall
    }
}

/// A module's preset sized to about `run.count` particles (their count goes as the
/// cube of the spacing) or elements of its space, simulated for `run.seconds`.
pub(crate) fn measure_preset(
    run: &PresetRun,
    overrides: &[String],
    backend: &Selected,
) -> anyhow::Result<PresetFigures> {
    let (sizing, counted) = match run.size {
        BenchSize::Particles => {
            let reference = load::from_preset(run.preset, overrides)?;
            let counted = Simulation::new_cpu(reference.clone())?.particle_count();
            let spacing = reference.particle_spacing * (counted as f32 / run.count as f32).cbrt();
            (vec![format!("particle_spacing={spacing}")], "particles")
        }
        BenchSize::Space(space, size) => (size(run.count), space),
    };
    let all: Vec<String> = sizing.iter().chain(overrides).cloned().collect();
    let mut sim = Simulation::new(load::from_preset(run.preset, &all)?, &*backend.factory)?;
    let kernels_before = sim.kernel_times();
    let t0 = Instant::now();
    while sim.time() < run.seconds {
        sim.step()?;
    }
    let wall = t0.elapsed().as_secs_f64();
    let steps = sim.steps();
    let count = match run.size {
        BenchSize::Particles => sim.particle_count(),
        BenchSize::Space(space, _) => sim.model().layout.count(space),
    };
    let reported = sim.measures();
    let measures = (run.measures.iter())
        .map(|&name| {
            let m = reported.iter().find(|m| m.name == name);
            (name.to_string(), m.map_or(f64::NAN, |m| m.value), m.map_or(String::new(), |m| m.unit.clone()))
        })
        .collect();
    Ok(PresetFigures {
        preset: run.preset,
        sizing,
        counted,
        count,
        simulated: sim.time(),
        steps,
        dt_mean: sim.stats().dt_mean,
        iterations: per_step_iterations(&sim, iterations(&sim), steps),
        wall,
        memory: peak_rss().filter(|_| run.memory).map(|b| b as f64 / count as f64),
        measures,
        passes: per_step(&kernels_before, &sim.kernel_times(), steps),
    })
}

/// [`measure_preset`], printed as a table (and the time per pass with `profile`).
fn run_preset(run: &PresetRun, overrides: &[String], backend: &Selected, profile: bool) -> anyhow::Result<()> {
    let f = measure_preset(run, overrides, backend)?;
    let counted = f.counted;
    println!("{} on {}, {}", f.preset, backend.description, f.sizing.join(", "));
    let heads: String = f.measures.iter().map(|(name, _, unit)| format!(" {name} {unit} |")).collect();
    println!(
        "| {counted} | simulated s | steps | dt mean s | solver iterations/step | wall s | ms/step | M {counted}-steps/s | real-time factor | peak RSS bytes/{counted} |{heads}"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|{}", "---:|".repeat(f.measures.len()));
    let values: String = f.measures.iter().map(|(_, v, _)| format!(" {} |", crate::figure::figure(*v))).collect();
    let memory = f.memory.map_or("-".into(), |b| format!("{b:.0}"));
    println!(
        "| {} | {:.3} | {} | {:.2e} | {} | {:.2} | {:.2} | {:.3} | {:.4} | {memory} |{values}",
        f.count,
        f.simulated,
        f.steps,
        f.dt_mean,
        f.iterations,
        f.wall,
        f.ms_per_step(),
        f.m_steps_per_second(),
        f.real_time_factor(),
    );
    if profile {
        print_profile(&format!("{} {counted} ({})", f.count, f.preset), &f.passes, backend.name);
    }
    Ok(())
}

/// Iterations of every iterative solve so far (0 for schemes that do not iterate).
fn iterations(sim: &Simulation) -> u64 {
    sim.stats().solves.values().map(|s| s.total_iterations).sum()
}

/// `solved` iterations over `steps` steps, or "-" for a scheme without solves.
fn per_step_iterations(sim: &Simulation, solved: u64, steps: u64) -> String {
    if sim.stats().solves.is_empty() { "-".into() } else { format!("{:.1}", solved as f64 / steps.max(1) as f64) }
}

/// Per kernel, device milliseconds and dispatches per step between two
/// [`floe_engine::Simulation::kernel_times`] readings `steps` steps apart, slowest first.
pub(crate) fn per_step(
    before: &[(&'static str, f64, u64)],
    after: &[(&'static str, f64, u64)],
    steps: u64,
) -> Vec<(&'static str, f64, f64)> {
    let mut out: Vec<_> = after
        .iter()
        .map(|&(label, s, d)| {
            let (s0, d0) = before.iter().find(|b| b.0 == label).map_or((0.0, 0), |b| (b.1, b.2));
            (label, (s - s0) * 1e3 / steps as f64, (d - d0) as f64 / steps as f64)
        })
        .collect();
    out.sort_by(|a, b| b.1.total_cmp(&a.1));
    out
}

/// Time to solution: simulate `seconds` of the dam break and compare the front.
fn solve(particles: usize, overrides: &[String], seconds: f64, backend: &Selected) -> anyhow::Result<()> {
    let mut sim = dam_break(particles, overrides, backend)?;
    println!("dam break ({}) on {}, to t = {seconds} s", sim.model().scheme.id, backend.description);
    let a = DAM_BREAK_A as f64;
    let d = sim.scene().particle_spacing as f64;
    let g = 9.81;
    let t_scale = (2.0 * g / a).sqrt();
    let mut history = vec![(0.0, dam_break::front(&sim.read(&[]).positions, 0.0, d, a))];
    let mut next = 0.01;
    let mut wall = 0.0;
    while sim.time() < seconds {
        let t0 = Instant::now();
        sim.step()?;
        wall += t0.elapsed().as_secs_f64();
        if sim.time() >= next {
            history.push((sim.time() * t_scale, dam_break::front(&sim.read(&[]).positions, 0.0, d, a)));
            next += 0.01;
        }
    }
    let reference = dam_break::reference(dam_break::KOSHIZUKA_OKA);
    let err = dam_break::compare(&history, &reference, 3.0);
    let at = |t: f64| history.iter().find(|h| h.0 >= t).map_or(f64::NAN, |h| h.1);
    println!(
        "| fluid particles | simulated s | steps | dt mean s | wall s | M particle-steps/s | front RMS (T<=3) | front max | front bias | Z(T=2) | solver iterations/step |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {} | {:.3} | {} | {:.2e} | {wall:.2} | {:.2} | {:.3} | {:.3} | {:+.3} | {:.3} | {} |",
        sim.particle_count(),
        sim.time(),
        sim.steps(),
        sim.stats().dt_mean,
        sim.particle_count() as f64 * sim.steps() as f64 / wall / 1e6,
        err.rms,
        err.max,
        err.bias,
        at(2.0),
        per_step_iterations(&sim, iterations(&sim), sim.steps())
    );
    Ok(())
}

/// `floe bench --lab`: a lab server under load (see [`crate::lab_bench`]).
fn lab(args: &BenchArgs) -> anyhow::Result<()> {
    let cfg = crate::lab_bench::LoadConfig {
        floe: std::env::current_exe()?,
        backend: format!("{:?}", args.backend).to_lowercase(),
        particles: args.particles[0],
        seconds: args.seconds,
        viewers: args.viewers,
        idle_viewers: args.idle_viewers.min(args.viewers),
        scripts: args.scripts,
        script_rate: args.script_rate,
    };
    let report = tokio::runtime::Runtime::new()?.block_on(crate::lab_bench::run(&cfg))?;
    crate::lab_bench::print(&cfg, &report);
    Ok(())
}

/// `floe bench --cluster`: a cluster under load through its proxy (see [`crate::lab_bench::cluster`]).
fn cluster(args: &BenchArgs) -> anyhow::Result<()> {
    let cfg = crate::lab_bench::cluster::ClusterLoad {
        floe: std::env::current_exe()?,
        seconds: args.seconds,
        viewers: args.viewers,
        scripts: args.scripts,
        script_rate: args.script_rate,
    };
    let report = tokio::runtime::Runtime::new()?.block_on(crate::lab_bench::cluster::run(&cfg))?;
    crate::lab_bench::cluster::print(&cfg, &report);
    Ok(())
}

/// `floe bench --step-latency`: Step calls' latency (see [`crate::lab_bench::step_latency`]).
fn step_latency(args: &BenchArgs) -> anyhow::Result<()> {
    let cfg = crate::lab_bench::step_latency::StepLatency {
        floe: std::env::current_exe()?,
        backend: format!("{:?}", args.backend).to_lowercase(),
        particles: args.particles.clone(),
        calls: args.steps,
    };
    let rows = tokio::runtime::Runtime::new()?.block_on(crate::lab_bench::step_latency::run(&cfg))?;
    crate::lab_bench::step_latency::print(&cfg, &rows);
    Ok(())
}
