//! The validation cases as `floe validate` runs them: one case, one resolution,
//! one variant of the solver options, timed, with the case's error norms.
//!
//! Each module declares its cases ([`crate::module::ModuleDef::cases`]): the preset
//! a case runs, its reference, resolutions, variants, bounds and how it measures its
//! errors. `floe validate` and its report pick them up from the registry.

use crate::Simulation;
use crate::guard::Halted;
use crate::scene::load::{SceneError, from_preset};
use crate::simulation::BackendFactory;
use serde::Serialize;

/// What a case's measurement returns: wall seconds stepping, the halt if the run
/// halted, and the error norms by name.
pub type Measured = (f64, Option<Halted>, Vec<(&'static str, f64)>);

/// A validation case: a preset at several resolutions and solver variants, compared
/// with a reference.
#[derive(Debug, Serialize)]
pub struct Case {
    /// Name as used on the command line and in reports.
    pub name: &'static str,
    /// The module that declares it.
    pub module: &'static str,
    /// What it is compared with: paper, equation, or docs/validation/cases.md section.
    pub reference: &'static str,
    /// The preset it runs (with `particle_spacing` and the variant's overrides).
    pub preset: &'static str,
    /// The norm plotted against wall time and used for the convergence order.
    pub primary_error: &'static str,
    /// Particle spacings (m), coarse to fine: `floe validate --quick` (CI) and `--full`.
    pub spacings: (&'static [f64], &'static [f64]),
    /// The bounds the case states, checked on the finest run of the first variant:
    /// (norm, largest allowed value).
    pub bounds: &'static [(&'static str, f64)],
    /// The spacing (m, one of the quick ones) at which `floe validate --bounds` (the
    /// test suite's run) checks the bounds on the first variant: the coarsest at
    /// which they hold, so every stated bound is checked in minutes while the reports
    /// show how the errors converge. `None` for a case with no quick spacing.
    pub checked_at: Option<f64>,
    /// The solver variants it runs, the defaults first.
    pub variants: &'static [Variant],
    /// Runs the built scene at `spacing` (m) and measures its errors.
    #[serde(skip)]
    pub measure: fn(&mut Simulation, f64) -> Measured,
}

impl Case {
    /// Resolutions (particle spacing, m), coarse to fine.
    pub fn spacings(&self, full: bool) -> &'static [f64] {
        if full { self.spacings.1 } else { self.spacings.0 }
    }

    /// The variant whose finest run the bounds are checked on.
    pub fn default_variant(&self) -> &'static str {
        self.variants.first().map_or("default", |v| v.name)
    }
}

/// Every case of every registered module.
pub fn all() -> Vec<&'static Case> {
    crate::module::all().iter().flat_map(|m| m.cases.iter()).collect()
}

/// A variant of the solver options, as `--set` overrides on the preset.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Variant {
    /// Short name (`default`, `mueller`, ...).
    pub name: &'static str,
    /// The overrides that make it.
    pub overrides: &'static [&'static str],
}

/// One validation run.
#[derive(Debug, Clone, Serialize)]
pub struct Outcome {
    /// The case's name.
    pub case: &'static str,
    /// The variant's name.
    pub variant: &'static str,
    /// Particle spacing (m).
    pub spacing: f64,
    /// Particles.
    pub particles: usize,
    /// Steps taken.
    pub steps: u64,
    /// Mean time step (s).
    pub dt_mean: f64,
    /// Wall seconds spent stepping.
    pub wall_seconds: f64,
    /// Error norms by name (see each case's docs).
    pub errors: Vec<(&'static str, f64)>,
    /// Each iterative solve's iterations and last residual over the run (schemes that iterate).
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub solves: std::collections::BTreeMap<String, crate::simulation::SolveStats>,
    /// The halt the user would have seen, if the run halted.
    pub halted: Option<String>,
}

impl Outcome {
    /// The error norm called `name`.
    pub fn error(&self, name: &str) -> Option<f64> {
        self.errors.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
    }
}

/// Runs `case` at `spacing` with `variant` on the backend `make` builds, `extra`
/// overrides applied before the variant's own (so a variant that sets the same field
/// keeps its value; an extra `particle_spacing` replaces `spacing`).
pub fn run(
    case: &'static Case,
    spacing: f64,
    variant: &Variant,
    extra: &[String],
    make: &BackendFactory,
) -> Result<Outcome, SceneError> {
    let mut overrides = vec![format!("particle_spacing={spacing}")];
    overrides.extend_from_slice(extra);
    overrides.extend(variant.overrides.iter().map(|s| s.to_string()));
    let scene = from_preset(case.preset, &overrides)?;
    // An extra `particle_spacing` wins over the ladder's: measure and report the one
    // run (its shortest decimal, as it was written, not the f32's widening).
    let spacing = match scene.particle_spacing {
        s if s == spacing as f32 => spacing,
        s => s.to_string().parse().expect("an f32 prints as a decimal"),
    };
    let mut sim = Simulation::new(scene, make).map_err(|e| SceneError::Invalid(vec![e.to_string()]))?;
    let (wall, halted, errors) = (case.measure)(&mut sim, spacing);
    Ok(Outcome {
        case: case.name,
        variant: variant.name,
        spacing,
        particles: sim.particle_count(),
        steps: sim.steps(),
        dt_mean: sim.stats().dt_mean,
        wall_seconds: wall,
        errors,
        solves: sim.stats().solves.clone(),
        halted: halted.map(|h| h.to_string()),
    })
}

/// Least-squares slope of `log(error)` against `log(spacing)`: the observed
/// order of convergence (positive when the error falls with the spacing).
/// `None` with fewer than two usable points.
pub fn convergence_order(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> =
        points.iter().filter(|(h, e)| *h > 0.0 && *e > 0.0 && e.is_finite()).map(|(h, e)| (h.ln(), e.ln())).collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let (mx, my) = (logs.iter().map(|p| p.0).sum::<f64>() / n, logs.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_checked_at_one_of_the_quick_spacings() {
        for case in all() {
            match case.checked_at {
                Some(h) => assert!(case.spacings(false).contains(&h), "{}: {h} is not a quick spacing", case.name),
                None => assert!(case.spacings(false).is_empty(), "{}: has quick spacings but none checked", case.name),
            }
        }
    }

    #[test]
    fn convergence_order_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025].iter().map(|&h| (h, 3.0 * h * h)).collect();
        assert!((convergence_order(&pts).unwrap() - 2.0).abs() < 1e-9);
        assert_eq!(convergence_order(&pts[..1]), None);
    }
}
