//! The stability battery (docs/validation/cases.md, last section): stiff and extreme
//! scenes that must either run to the end staying finite and physical, or stop
//! with a clear error. A scene that goes non-finite without halting is a failure.
//!
//! For each case the largest stable time step is found by bisection on the
//! CFL number of the step control (`solver.time_step.cfl`, up to 2, the
//! largest a scene accepts).

use super::{energy, run_probed};
use crate::Simulation;
use crate::scene::load::{SceneError, from_preset};
use crate::simulation::BackendFactory;
use serde::Serialize;

/// What a case must do to pass.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Expect {
    /// Run to the end.
    Finish,
    /// Run to the end, or halt with a reason (an impossible start state).
    FinishOrHalt,
    /// Run to the end with no particle farther than this many particle spacings
    /// from where it started (a material strong enough to hold: it must not creep).
    StayPut(f64),
}

/// One stiff or extreme scene: a preset with overrides. Modules declare theirs
/// ([`crate::module::ModuleDef::stability`]).
#[derive(Debug, Clone, Serialize)]
pub struct StabilityCase {
    /// Short name.
    pub name: &'static str,
    /// What is extreme about it.
    pub what: &'static str,
    /// The preset it starts from.
    pub preset: &'static str,
    /// Particle spacing (m) in quick and full mode.
    pub spacing: (f64, f64),
    /// Overrides on the preset.
    pub overrides: &'static [&'static str],
    /// Simulated seconds in quick and full mode.
    pub until: (f64, f64),
    /// What passing means.
    pub expect: Expect,
}

/// Every stability case of every registered module.
pub fn all() -> Vec<&'static StabilityCase> {
    crate::module::all().iter().flat_map(|m| m.stability.iter()).collect()
}

/// One run of a stability case.
#[derive(Debug, Clone, Serialize)]
pub struct Trial {
    /// Whether it reached its end time.
    pub finished: bool,
    /// The error the user saw, if it halted.
    pub halted: Option<String>,
    /// Non-finite state without a halt: the failure the battery exists to catch.
    pub silent_explosion: bool,
    /// Largest compression seen.
    pub max_density_deviation: f64,
    /// `(max_t E(t) - E(0)) / |E(0)|`, mechanical energy (see [`energy`]).
    pub energy_growth: f64,
    /// Steps and sub-steps taken.
    pub steps: u64,
    /// Sub-steps forced by a fixed dt above the limit.
    pub substeps: u64,
    /// Mean dt (s).
    pub dt_mean: f64,
    /// Wall seconds stepping.
    pub wall_seconds: f64,
    /// Fluid particles.
    pub particles: usize,
    /// Farthest any particle ended from where it started (m).
    pub max_displacement: f64,
    /// Particle spacing (m).
    pub spacing: f64,
    /// The scene's measures at the end (solver iterations, module measures).
    pub measures: Vec<crate::simulation::Measure>,
}

/// A case's result: the run at default settings and the bisection.
#[derive(Debug, Clone, Serialize)]
pub struct StabilityOutcome {
    /// The case.
    pub case: StabilityCase,
    /// The run at the scene's own settings.
    pub trial: Trial,
    /// Largest CFL number that ran stably (2.0 means the whole range was stable).
    pub largest_stable_cfl: Option<f64>,
    /// Mean dt (s) of the run at that CFL number.
    pub largest_stable_dt: Option<f64>,
    /// Whether the case met its expectation.
    pub passed: bool,
}

/// Runs one trial of `case` on the backend `make` builds: `first` overrides before
/// the case's own, `extra` after them.
pub fn trial(
    case: &StabilityCase,
    full: bool,
    first: &[String],
    extra: &[String],
    make: &BackendFactory,
) -> Result<Trial, SceneError> {
    let spacing = if full { case.spacing.1 } else { case.spacing.0 };
    let mut overrides = vec![format!("particle_spacing={spacing}")];
    overrides.extend_from_slice(first);
    overrides.extend(case.overrides.iter().map(|s| s.to_string()));
    overrides.extend_from_slice(extra);
    let scene = from_preset(case.preset, &overrides)?;
    let g = scene.gravity;
    let mut sim = Simulation::new(scene, make).map_err(|e| SceneError::Invalid(vec![e.to_string()]))?;
    let mass = sim.particle_mass() as f64;
    let start = sim.read(&[]).positions;
    let mut energies = Vec::new();
    let until = if full { case.until.1 } else { case.until.0 };
    let (wall, halted) = run_probed(&mut sim, until, until / 50.0, |s| {
        energies.push(energy::mechanical(&s.read(&["velocity"]), mass, g));
    });
    let last = sim.read(&["velocity", "density"]);
    let finite = last.positions.iter().flatten().all(|v| v.is_finite())
        && last.channels.iter().all(|(_, v)| (0..v.len()).flat_map(|i| v.get(i)).all(f32::is_finite));
    let max_displacement = start
        .iter()
        .zip(&last.positions)
        .map(|(a, b)| a.iter().zip(b).map(|(p, q)| f64::from(p - q).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let e0 = energies.first().copied().unwrap_or(0.0);
    let e_max = energies.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok(Trial {
        finished: halted.is_none(),
        silent_explosion: halted.is_none() && !finite,
        halted: halted.map(|h| h.to_string()),
        max_density_deviation: sim.stats().max_density_deviation,
        energy_growth: if e0.abs() > 0.0 { (e_max - e0) / e0.abs() } else { e_max - e0 },
        steps: sim.steps(),
        substeps: sim.substeps(),
        dt_mean: sim.stats().dt_mean,
        wall_seconds: wall,
        particles: sim.particle_count(),
        max_displacement,
        spacing,
        measures: sim.measures(),
    })
}

/// Runs `case` at its own settings (`overrides` applied before the case's own),
/// then bisects the CFL number (`iterations` halvings between the default 0.5 and 2)
/// for the largest stable step.
pub fn run(
    case: &StabilityCase,
    full: bool,
    iterations: u32,
    overrides: &[String],
    make: &BackendFactory,
) -> Result<StabilityOutcome, SceneError> {
    let base = trial(case, full, overrides, &[], make)?;
    let stable = |t: &Trial| t.finished && !t.silent_explosion;
    let at = |cfl: f64| trial(case, full, overrides, &[format!("solver.time_step.cfl={cfl}")], make);
    let mut best: Option<(f64, f64)> = None;
    if stable(&base) {
        let top = at(2.0)?;
        if stable(&top) {
            best = Some((2.0, top.dt_mean));
        } else {
            let (mut lo, mut hi) = (0.5, 2.0);
            best = Some((lo, base.dt_mean));
            for _ in 0..iterations {
                let mid = 0.5 * (lo + hi);
                let t = at(mid)?;
                if stable(&t) {
                    lo = mid;
                    best = Some((mid, t.dt_mean));
                } else {
                    hi = mid;
                }
            }
        }
    }
    let passed = !base.silent_explosion
        && match case.expect {
            Expect::Finish => base.finished,
            Expect::FinishOrHalt => base.finished || base.halted.is_some(),
            Expect::StayPut(spacings) => base.finished && base.max_displacement <= spacings * base.spacing,
        };
    Ok(StabilityOutcome {
        case: case.clone(),
        largest_stable_cfl: best.map(|b| b.0),
        largest_stable_dt: best.map(|b| b.1),
        trial: base,
        passed,
    })
}
