//! `floe validate`: every supported case of docs/validation/cases.md at several resolutions
//! and solver variants, plus the stability battery; writes `report.md`,
//! `report.json` and SVG plots, and fails when a stated bound is not met.

mod plot;
pub(crate) mod report;

use crate::cli::ValidateArgs;
use anyhow::{Context, bail};
use floe_engine::simulation::BackendFactory;
use floe_engine::validation::cases::{self, Case, Outcome};
use floe_engine::validation::stability::{self, StabilityOutcome};
use std::io::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Everything one `floe validate` produced.
#[derive(Debug, serde::Serialize)]
pub struct Report {
    /// The command line, for re-running.
    pub command: String,
    /// UTC date of the run (YYYY-MM-DD).
    pub date: String,
    /// The machine: cores and CPU model.
    pub machine: String,
    /// `quick` or `full`.
    pub mode: &'static str,
    /// Backend the runs used (and its device).
    pub backend: String,
    /// Every accuracy run.
    pub runs: Vec<Outcome>,
    /// The stability battery.
    pub stability: Vec<StabilityOutcome>,
    /// Failed checks, one line each; empty when all passed.
    pub failures: Vec<String>,
}

/// Which runs a validation makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Every variant at the quick spacings; bounds checked on the finest.
    Quick,
    /// Every variant at the full spacings.
    Full,
    /// Each case's first variant at the spacing its bounds are checked at.
    Bounds,
}

impl Mode {
    fn name(self) -> &'static str {
        match self {
            Mode::Quick => "quick",
            Mode::Full => "full",
            Mode::Bounds => "bounds",
        }
    }
}

/// One run of a validation.
#[derive(Debug, Clone, Copy)]
enum Job {
    /// A case's variant at a spacing (m).
    Run(&'static Case, &'static cases::Variant, f64),
    /// A stability case.
    Stability(&'static stability::StabilityCase),
}

/// What a job gave.
#[derive(Debug)]
enum Done {
    Run(Outcome),
    Stability(StabilityOutcome),
}

/// Runs the validation and writes the report into `args.out`.
pub fn validate(args: ValidateArgs) -> anyhow::Result<()> {
    let mode = if args.full {
        Mode::Full
    } else if args.bounds {
        Mode::Bounds
    } else {
        Mode::Quick
    };
    let (chosen_cases, chosen_stability) = select(&args.cases)?;
    let backend = floe_gpu::select::select(args.backend.into())?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let mut jobs = Vec::new();
    for &case in &chosen_cases {
        match mode {
            Mode::Bounds => {
                if let (Some(variant), Some(h)) = (case.variants.first(), case.checked_at) {
                    jobs.push(Job::Run(case, variant, h));
                }
            }
            Mode::Quick | Mode::Full => {
                for variant in case.variants {
                    jobs.extend(case.spacings(mode == Mode::Full).iter().map(|&h| Job::Run(case, variant, h)));
                }
            }
        }
    }
    jobs.extend(chosen_stability.iter().map(|&c| Job::Stability(c)));
    let done = run_jobs(&jobs, args.jobs.max(1), mode == Mode::Full, &args.overrides, &*backend.factory)?;
    let (mut runs, mut battery) = (Vec::new(), Vec::new());
    for d in done {
        match d {
            Done::Run(o) => runs.push(o),
            Done::Stability(o) => battery.push(o),
        }
    }
    let failures = failures(&chosen_cases, &runs, &battery, mode);
    let report = Report {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        date: report::today(),
        machine: report::machine(),
        mode: mode.name(),
        backend: backend.description.clone(),
        runs,
        stability: battery,
        failures,
    };
    report::write(&args.out, &report)?;
    eprintln!("report: {}", args.out.join("report.md").display());
    if !report.failures.is_empty() {
        bail!("validation failed:\n{}", report.failures.join("\n"));
    }
    Ok(())
}

/// Runs `jobs` on `workers` threads at once, each with a share of the cores (a small
/// scene steps little faster on two cores than on one, so two at once take about
/// half the time); prints each as it ends; returns the outcomes in job order.
fn run_jobs(
    jobs: &[Job],
    workers: usize,
    full: bool,
    overrides: &[String],
    make: &BackendFactory,
) -> anyhow::Result<Vec<Done>> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = (cores / workers).max(1);
    let next = AtomicUsize::new(0);
    let finished = Mutex::new(0usize);
    let results: Vec<Mutex<Option<anyhow::Result<Done>>>> = jobs.iter().map(|_| Mutex::new(None)).collect();
    let work = || -> anyhow::Result<()> {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(&job) = jobs.get(k) else { return Ok(()) };
            let done = pool.install(|| run_job(job, full, overrides, make));
            let line = done.as_ref().map_or_else(|e| format!("{e:#}"), describe);
            let mut n = finished.lock().expect("progress lock");
            *n += 1;
            eprintln!("[{:>3}/{}] {line}", *n, jobs.len());
            let _ = std::io::stderr().flush();
            *results[k].lock().expect("result lock") = Some(done);
        }
    };
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..workers.min(jobs.len()).max(1)).map(|_| s.spawn(work)).collect();
        handles.into_iter().try_for_each(|h| h.join().expect("a validation worker"))
    })?;
    results.into_iter().map(|r| r.into_inner().expect("result lock").expect("every job ran")).collect()
}

fn run_job(job: Job, full: bool, overrides: &[String], make: &BackendFactory) -> anyhow::Result<Done> {
    Ok(match job {
        Job::Run(case, variant, spacing) => Done::Run(cases::run(case, spacing, variant, overrides, make)?),
        Job::Stability(case) => Done::Stability(stability::run(case, full, if full { 5 } else { 3 }, overrides, make)?),
    })
}

/// One progress line.
fn describe(done: &Done) -> String {
    match done {
        Done::Run(o) => {
            let primary = cases::all().iter().find(|c| c.name == o.case).map_or("", |c| c.primary_error);
            format!(
                "{} {} spacing {:.4} m: {} particles, {} steps, {:.1} s, {} {}{}",
                o.case,
                o.variant,
                o.spacing,
                o.particles,
                o.steps,
                o.wall_seconds,
                primary,
                crate::figure::figure(o.error(primary).unwrap_or(f64::NAN)),
                o.halted.as_deref().map(|h| format!(" HALTED: {h}")).unwrap_or_default()
            )
        }
        Done::Stability(o) => format!(
            "stability {}: {}, max density deviation {:.1} %, largest stable CFL {}{}",
            o.case.name,
            if o.trial.finished { "finished" } else { "halted" },
            o.trial.max_density_deviation * 100.0,
            o.largest_stable_cfl.map_or("-".into(), |c| format!("{c:.3}")),
            if o.passed { "" } else { "  FAILED" }
        ),
    }
}

/// Resolves `--case` names into accuracy cases and stability cases (all when empty).
fn select(names: &[String]) -> anyhow::Result<(Vec<&'static Case>, Vec<&'static stability::StabilityCase>)> {
    let (all, battery) = (cases::all(), stability::all());
    if names.is_empty() {
        return Ok((all, battery));
    }
    let (mut c, mut s) = (Vec::new(), Vec::new());
    for name in names {
        if let Some(case) = all.iter().find(|c| c.name == name) {
            c.push(*case);
        } else if name == "stability" {
            s.extend(battery.iter().copied());
        } else if let Some(case) = battery.iter().find(|c| c.name == name) {
            s.push(*case);
        } else {
            let known: Vec<&str> =
                all.iter().map(|c| c.name).chain(["stability"]).chain(battery.iter().map(|c| c.name)).collect();
            bail!("unknown case '{name}'; cases are: {}", known.join(", "));
        }
    }
    Ok((c, s))
}

/// The bounds each case states, checked on the finest default run (in `--bounds`
/// mode the case's one run), and the
/// battery's expectations.
fn failures(cases: &[&Case], runs: &[Outcome], battery: &[StabilityOutcome], mode: Mode) -> Vec<String> {
    let mut out = Vec::new();
    for &case in cases {
        // A bounds run is the case's one run; the reports check their finest.
        let finest = runs
            .iter()
            .filter(|o| o.case == case.name && o.variant == case.default_variant())
            .filter(|o| mode != Mode::Bounds || Some(o.spacing) == case.checked_at)
            .min_by(|a, b| a.spacing.total_cmp(&b.spacing));
        let Some(finest) = finest else { continue };
        if let Some(h) = &finest.halted {
            out.push(format!("{}: finest default run halted: {h}", case.name));
            continue;
        }
        for &(norm, bound) in case.bounds {
            let v = finest.error(norm).unwrap_or(f64::NAN);
            if v.is_nan() || v > bound {
                out.push(format!(
                    "{}: {norm} = {} exceeds its bound {bound} (spacing {} m)",
                    case.name,
                    crate::figure::figure(v),
                    finest.spacing
                ));
            }
        }
    }
    for o in battery.iter().filter(|o| !o.passed) {
        let what = if o.trial.silent_explosion {
            "went non-finite without halting".to_string()
        } else {
            format!("did not finish: {}", o.trial.halted.as_deref().unwrap_or("?"))
        };
        out.push(format!("stability {}: {what}", o.case.name));
    }
    out
}
