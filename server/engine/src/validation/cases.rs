//! The validation cases as `floe validate` runs them: one case, one resolution,
//! one variant of the solver options, timed, with the case's error norms.

use super::{dam_break, hydrostatic, run_probed};
use crate::Simulation;
use crate::scene::load::{SceneError, from_preset};
use crate::scene::presets::DAM_BREAK_A;
use crate::simulation::BackendFactory;
use serde::Serialize;

/// A validation case this engine supports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Case {
    /// VALIDATION.md case 1: a column at rest, `p = rho0 g (H - y)`.
    Hydrostatic,
    /// VALIDATION.md case 2: surge front against Koshizuka & Oka (1996).
    DamBreak,
}

impl Case {
    /// Every supported case.
    pub const ALL: [Case; 2] = [Case::Hydrostatic, Case::DamBreak];

    /// Name as used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Case::Hydrostatic => "hydrostatic",
            Case::DamBreak => "dam_break",
        }
    }

    /// The norm plotted against wall time and used for the convergence order.
    pub fn primary_error(self) -> &'static str {
        match self {
            Case::Hydrostatic => "pressure_l2",
            Case::DamBreak => "front_rms",
        }
    }

    /// Resolutions (particle spacing, m), coarse to fine.
    pub fn spacings(self, full: bool) -> Vec<f64> {
        let a = DAM_BREAK_A as f64;
        match (self, full) {
            (Case::Hydrostatic, false) => vec![0.05, 0.0375, 0.025],
            (Case::Hydrostatic, true) => vec![0.05, 0.0375, 0.025, 0.01875],
            (Case::DamBreak, false) => vec![a / 8.0, a / 12.0, a / 16.0],
            (Case::DamBreak, true) => vec![a / 12.0, a / 16.0, a / 22.0, a / 28.0],
        }
    }

    /// The bounds the case states, checked on the finest run of the default variant:
    /// (norm, largest allowed value).
    pub fn bounds(self) -> &'static [(&'static str, f64)] {
        match self {
            Case::Hydrostatic => &[("pressure_l2", 0.05), ("mean_density_deviation", 0.01)],
            Case::DamBreak => &[("front_max_t2_5", 0.35)],
        }
    }
}

/// A variant of the solver options, as `--set` overrides on the preset.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Variant {
    /// Short name (`default`, `mueller`, ...).
    pub name: &'static str,
    /// The overrides that make it.
    pub overrides: &'static [&'static str],
}

/// The variants every case runs: the defaults, then one option changed at a time.
pub const VARIANTS: &[Variant] = &[
    Variant { name: "default", overrides: &[] },
    Variant { name: "mueller_kernels", overrides: &["solver.kernel=mueller"] },
    Variant { name: "leapfrog", overrides: &["solver.integrator=leapfrog"] },
    Variant {
        name: "laplacian_viscosity",
        overrides: &["fluids[0].viscosity={\"model\":\"laplacian\",\"nu\":1e-6}", "fluids[0].xsph=0.05"],
    },
];

/// One validation run.
#[derive(Debug, Clone, Serialize)]
pub struct Outcome {
    /// The case.
    pub case: Case,
    /// The variant's name.
    pub variant: &'static str,
    /// Particle spacing (m).
    pub spacing: f64,
    /// Fluid particles.
    pub particles: usize,
    /// Steps taken.
    pub steps: u64,
    /// Mean time step (s).
    pub dt_mean: f64,
    /// Wall seconds spent stepping.
    pub wall_seconds: f64,
    /// Error norms by name (see each case's docs).
    pub errors: Vec<(&'static str, f64)>,
    /// The halt the user would have seen, if the run halted.
    pub halted: Option<String>,
}

impl Outcome {
    /// The error norm called `name`.
    pub fn error(&self, name: &str) -> Option<f64> {
        self.errors.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
    }
}

/// Runs `case` at `spacing` with `variant` on the backend `make` builds.
pub fn run(case: Case, spacing: f64, variant: &Variant, make: &BackendFactory) -> Result<Outcome, SceneError> {
    let mut overrides = vec![format!("particle_spacing={spacing}")];
    overrides.extend(variant.overrides.iter().map(|s| s.to_string()));
    let scene = from_preset(case.name(), &overrides)?;
    let mut sim = Simulation::new(scene, make).map_err(|e| SceneError::Invalid(vec![e.to_string()]))?;
    let (wall, halted, errors) = match case {
        Case::Hydrostatic => run_hydrostatic(&mut sim, spacing),
        Case::DamBreak => run_dam_break(&mut sim, spacing),
    };
    Ok(Outcome {
        case,
        variant: variant.name,
        spacing,
        particles: sim.particle_count(),
        steps: sim.steps(),
        dt_mean: sim.stats().dt_mean,
        wall_seconds: wall,
        errors,
        halted: halted.map(|h| h.to_string()),
    })
}

type Measured = (f64, Option<crate::Halted>, Vec<(&'static str, f64)>);

/// Settles for the preset's damped 0.5 s, runs undamped to 1 s, then compares
/// with `rho0 g (H - y)` for H = 0.9 m (Adami et al. 2012).
fn run_hydrostatic(sim: &mut Simulation, spacing: f64) -> Measured {
    let (wall, halted) = run_probed(sim, 1.0, 1.0, |_| {});
    let p = sim.read(&["velocity", "density", "pressure"]);
    let e = hydrostatic::measure(&p, 1000.0, 9.81, 0.9, spacing);
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    let ke = v.iter().map(|v| 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) as f64).sum::<f64>() / v.len() as f64;
    let errors = vec![
        ("pressure_l2", e.pressure_l2),
        ("pressure_linf", e.pressure_linf),
        ("mean_density_deviation", e.mean_density_deviation),
        ("surface_drift_m", e.surface - 0.9),
        ("kinetic_energy_j_per_kg", ke),
    ];
    (wall, halted, errors)
}

/// Runs to T = 3.1 and compares the front with Koshizuka & Oka for T <= 3 and T <= 2.5.
fn run_dam_break(sim: &mut Simulation, spacing: f64) -> Measured {
    let (a, g) = (DAM_BREAK_A as f64, 9.81);
    let t_scale = (2.0 * g / a).sqrt();
    let mut history = Vec::new();
    let (wall, halted) = run_probed(sim, dam_break::seconds(3.1, g, a), 0.005, |s| {
        history.push((s.time() * t_scale, dam_break::front(&s.read(&[]).positions, 0.0, spacing, a)));
    });
    let reference = dam_break::reference(dam_break::KOSHIZUKA_OKA);
    let e3 = dam_break::compare(&history, &reference, 3.0);
    let e25 = dam_break::compare(&history, &reference, 2.5);
    let errors =
        vec![("front_rms", e3.rms), ("front_max", e3.max), ("front_bias", e3.bias), ("front_max_t2_5", e25.max)];
    (wall, halted, errors)
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
    fn convergence_order_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025].iter().map(|&h| (h, 3.0 * h * h)).collect();
        assert!((convergence_order(&pts).unwrap() - 2.0).abs() < 1e-9);
        assert_eq!(convergence_order(&pts[..1]), None);
    }
}
