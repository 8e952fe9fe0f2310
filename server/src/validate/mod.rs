//! `floe validate`: every supported case of VALIDATION.md at several resolutions
//! and solver variants, plus the stability battery; writes `report.md`,
//! `report.json` and SVG plots, and fails when a stated bound is not met.

mod plot;
mod report;

use crate::cli::ValidateArgs;
use anyhow::{Context, bail};
use floe_engine::validation::cases::{self, Case, Outcome};
use floe_engine::validation::stability::{self, StabilityOutcome};
use std::io::Write;

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

/// Runs the validation and writes the report into `args.out`.
pub fn validate(args: ValidateArgs) -> anyhow::Result<()> {
    let full = args.full;
    let (chosen_cases, chosen_stability) = select(&args.cases)?;
    let backend = floe_gpu::select::select(args.backend.into())?;
    let make = &*backend.factory;
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let total =
        chosen_cases.iter().map(|c| c.spacings(full).len() * c.variants.len()).sum::<usize>() + chosen_stability.len();
    let mut done = 0;
    let mut note = |line: String| {
        done += 1;
        eprintln!("[{done:>3}/{total}] {line}");
        let _ = std::io::stderr().flush();
    };
    let mut runs = Vec::new();
    for &case in &chosen_cases {
        for variant in case.variants {
            for &spacing in case.spacings(full) {
                let o = cases::run(case, spacing, variant, make)?;
                note(format!(
                    "{} {} spacing {:.4} m: {} particles, {} steps, {:.1} s, {} {:.4}{}",
                    case.name,
                    variant.name,
                    spacing,
                    o.particles,
                    o.steps,
                    o.wall_seconds,
                    case.primary_error,
                    o.error(case.primary_error).unwrap_or(f64::NAN),
                    o.halted.as_deref().map(|h| format!(" HALTED: {h}")).unwrap_or_default()
                ));
                runs.push(o);
            }
        }
    }
    let mut battery = Vec::new();
    for case in &chosen_stability {
        let o = stability::run(case, full, if full { 5 } else { 3 }, make)?;
        note(format!(
            "stability {}: {}, max density deviation {:.1} %, largest stable CFL {}{}",
            case.name,
            if o.trial.finished { "finished" } else { "halted" },
            o.trial.max_density_deviation * 100.0,
            o.largest_stable_cfl.map_or("-".into(), |c| format!("{c:.3}")),
            if o.passed { "" } else { "  FAILED" }
        ));
        battery.push(o);
    }
    let failures = failures(&chosen_cases, &runs, &battery);
    let report = Report {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        date: report::today(),
        machine: report::machine(),
        mode: if full { "full" } else { "quick" },
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

/// The bounds each case states, checked on the finest default run, and the
/// battery's expectations.
fn failures(cases: &[&Case], runs: &[Outcome], battery: &[StabilityOutcome]) -> Vec<String> {
    let mut out = Vec::new();
    for &case in cases {
        let finest = runs
            .iter()
            .filter(|o| o.case == case.name && o.variant == case.default_variant())
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
                    "{}: {norm} = {v:.4} exceeds its bound {bound} (spacing {} m)",
                    case.name, finest.spacing
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
