//! Writing a validation [`Report`]: `report.json` (everything), `report.md`
//! (tables, convergence orders, the battery, links to the plots) and SVG plots.

use super::Report;
use super::plot::{Series, loglog};
use floe_engine::validation::cases::{self, convergence_order};
use std::fmt::Write as _;
use std::path::Path;

/// Today's UTC date as YYYY-MM-DD (civil-from-days, Howard Hinnant's algorithm).
pub fn today() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

/// Cores and CPU model of this machine.
pub fn machine() -> String {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("model name")).map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    format!("{cores} cores, {model}, {}", std::env::consts::ARCH)
}

/// Writes report.json, report.md and the plots into `dir`.
pub fn write(dir: &Path, r: &Report) -> anyhow::Result<()> {
    std::fs::write(dir.join("report.json"), serde_json::to_string_pretty(r)? + "\n")?;
    let mut md = String::new();
    writeln!(md, "# Floe validation report ({})\n", r.mode)?;
    writeln!(
        md,
        "- command: `{}`\n- date: {}\n- machine: {}\n- backend: {}\n",
        r.command, r.date, r.machine, r.backend
    )?;
    if r.failures.is_empty() {
        writeln!(md, "**All stated bounds met.**\n")?;
    } else {
        writeln!(md, "**Failed checks:**\n")?;
        for f in &r.failures {
            writeln!(md, "- {f}")?;
        }
        writeln!(md)?;
    }
    for case in cases::all() {
        let runs: Vec<_> = r.runs.iter().filter(|o| o.case == case.name).collect();
        if runs.is_empty() {
            continue;
        }
        let primary = case.primary_error;
        writeln!(md, "## {}\n", case.name)?;
        writeln!(md, "Reference: {} (module `{}`).\n", case.reference, case.module)?;
        let bounds: Vec<String> = case.bounds.iter().map(|(n, b)| format!("{n} <= {b}")).collect();
        writeln!(md, "Bounds (finest {} run): {}.\n", case.default_variant(), bounds.join(", "))?;
        let mut work = Vec::<Series>::new();
        let mut conv = Vec::<Series>::new();
        writeln!(md, "| variant | observed order of {primary} in spacing |\n|---|---:|")?;
        for v in case.variants {
            let mine: Vec<_> = runs.iter().filter(|o| o.variant == v.name && o.halted.is_none()).collect();
            let pts: Vec<(f64, f64)> = mine.iter().filter_map(|o| Some((o.spacing, o.error(primary)?))).collect();
            let order = convergence_order(&pts).map_or("-".into(), |p| format!("{p:.2}"));
            writeln!(md, "| {} | {order} |", v.name)?;
            work.push((v.name.into(), mine.iter().filter_map(|o| Some((o.wall_seconds, o.error(primary)?))).collect()));
            conv.push((v.name.into(), pts));
        }
        let name = case.name;
        loglog(
            &dir.join(format!("{name}_work_precision.svg")),
            &format!("{name}: {primary} against run time"),
            "wall seconds",
            primary,
            &work,
        )?;
        loglog(
            &dir.join(format!("{name}_convergence.svg")),
            &format!("{name}: {primary} against spacing"),
            "particle spacing (m)",
            primary,
            &conv,
        )?;
        writeln!(md, "\n![work-precision]({name}_work_precision.svg)\n![convergence]({name}_convergence.svg)\n")?;
        let norms: Vec<&str> = runs[0].errors.iter().map(|(n, _)| *n).collect();
        writeln!(
            md,
            "| variant | spacing m | particles | steps | dt mean s | wall s | {} | iterations (mean/max) | halted |",
            norms.join(" | ")
        )?;
        writeln!(md, "|---|---:|---:|---:|---:|---:|{}---|---|", "---:|".repeat(norms.len()))?;
        for o in &runs {
            let errs: Vec<String> = o.errors.iter().map(|(_, v)| crate::figure::figure(*v)).collect();
            let solves: Vec<String> = o
                .solves
                .iter()
                .map(|(name, s)| format!("{name} {:.1}/{}", s.mean_iterations, s.max_iterations))
                .collect();
            writeln!(
                md,
                "| {} | {:.4} | {} | {} | {:.2e} | {:.2} | {} | {} | {} |",
                o.variant,
                o.spacing,
                o.particles,
                o.steps,
                o.dt_mean,
                o.wall_seconds,
                errs.join(" | "),
                if solves.is_empty() { "-".into() } else { solves.join(", ") },
                o.halted.as_deref().unwrap_or("")
            )?;
        }
        writeln!(md)?;
    }
    if !r.stability.is_empty() {
        writeln!(md, "## Stability battery\n")?;
        writeln!(
            md,
            "Presets made stiff or extreme (each case names its preset). Largest stable step: bisection on the CFL number (2.0 = the whole range was stable).\n"
        )?;
        writeln!(
            md,
            "| case | preset | what | particles | result | max density deviation | energy growth | steps (sub-steps) | mean dt s | farthest particle moved m | largest stable CFL | its mean dt s | error the user saw | passed |"
        )?;
        writeln!(md, "|---|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|---|")?;
        for o in &r.stability {
            let t = &o.trial;
            writeln!(
                md,
                "| {} | {} | {} | {} | {} | {:.2} % | {:+.3} | {} ({}) | {:.2e} | {:.2e} | {} | {} | {} | {} |",
                o.case.name,
                o.case.preset,
                o.case.what,
                t.particles,
                if t.finished {
                    "finished"
                } else if t.silent_explosion {
                    "SILENT EXPLOSION"
                } else {
                    "halted"
                },
                t.max_density_deviation * 100.0,
                t.energy_growth,
                t.steps,
                t.substeps,
                t.dt_mean,
                t.max_displacement,
                o.largest_stable_cfl.map_or("-".into(), |c| format!("{c:.3}")),
                o.largest_stable_dt.map_or("-".into(), |d| format!("{d:.2e}")),
                t.halted.as_deref().unwrap_or(""),
                if o.passed { "yes" } else { "NO" }
            )?;
        }
        writeln!(md, "\nWhat the modules measured at the end of each run:\n")?;
        for o in &r.stability {
            let module: Vec<String> = o
                .trial
                .measures
                .iter()
                .filter(|m| m.name.contains('.'))
                .map(|m| format!("{} {:.3e} {}", m.name, m.value, m.unit).trim_end().to_string())
                .collect();
            if !module.is_empty() {
                writeln!(md, "- {}: {}", o.case.name, module.join(", "))?;
            }
        }
    }
    std::fs::write(dir.join("report.md"), md)?;
    Ok(())
}
