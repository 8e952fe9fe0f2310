//! The fluid module's validation cases (docs/validation/cases.md §1 and §2) and its stability
//! battery (docs/validation/cases.md, last section): the dam break made stiff or extreme.

use crate::Simulation;
use crate::modules::fluid::presets::DAM_BREAK_A;
use crate::modules::fluid::presets::{POISEUILLE, TAYLOR_GREEN, TAYLOR_GREEN_WCSPH};
use crate::modules::fluid::spec::TaylorGreen;
use crate::validation::cases::{Case, Measured, Variant};
use crate::validation::stability::{Expect, StabilityCase};
use crate::validation::{dam_break, hydrostatic, poiseuille, run_probed, taylor_green};

const A: f64 = DAM_BREAK_A as f64;

/// The variants the hydrostatic case runs: the preset (DFSPH, conjugate gradients,
/// Wendland's kernel), on the cubic spline, with DFSPH's Jacobi solves, and WCSPH
/// with δ-SPH (the preset until 2026-12-06) with one of its options changed at a
/// time: the kernels, the integrator, the viscosity, the density summed instead of
/// integrated.
const HYDROSTATIC_VARIANTS: [Variant; 8] = [
    Variant { name: "default", overrides: &[] },
    Variant { name: "cubic_spline", overrides: &[CUBIC] },
    Variant { name: "jacobi", overrides: &[JACOBI, CUBIC] },
    Variant { name: "wcsph", overrides: &[WCSPH, CUBIC, DELTA_SPH] },
    Variant { name: "wcsph_mueller_kernels", overrides: &[WCSPH, DELTA_SPH, "solver.kernel=mueller"] },
    Variant { name: "wcsph_leapfrog", overrides: &[WCSPH, CUBIC, DELTA_SPH, "solver.integrator=leapfrog"] },
    Variant { name: "wcsph_laplacian_viscosity", overrides: &[WCSPH, CUBIC, DELTA_SPH, LAPLACIAN[0], LAPLACIAN[1]] },
    Variant { name: "wcsph_summation", overrides: &[WCSPH, CUBIC] },
];

/// The variants the dam break runs: the preset (DFSPH), the other scheme, and WCSPH
/// with one of its options changed at a time (the kernels, the integrator, the
/// viscosity, δ-SPH), so each row compares with the `wcsph` row.
const DAM_BREAK_VARIANTS: [Variant; 6] = [
    Variant { name: "default", overrides: &[] },
    Variant { name: "wcsph", overrides: &[WCSPH] },
    Variant { name: "wcsph_mueller_kernels", overrides: &[WCSPH, "solver.kernel=mueller"] },
    Variant { name: "wcsph_leapfrog", overrides: &[WCSPH, "solver.integrator=leapfrog"] },
    Variant { name: "wcsph_laplacian_viscosity", overrides: &[WCSPH, LAPLACIAN[0], LAPLACIAN[1]] },
    Variant { name: "wcsph_delta_sph", overrides: &[WCSPH, "solver.delta_sph={\"delta\":0.1}"] },
];

const WCSPH: &str = "solver.method=\"wcsph\"";
const DFSPH: &str = "solver.method=\"dfsph\"";
const JACOBI: &str = "solver.dfsph.solver=\"jacobi\"";
const CUBIC: &str = "solver.kernel=\"cubic_spline\"";
const DELTA_SPH: &str = "solver.delta_sph={\"delta\":0.1}";

/// Laplacian viscosity of water with a little XSPH smoothing, in place of the
/// presets' artificial viscosity.
const LAPLACIAN: &[&str] = &["fluids[0].viscosity={\"model\":\"laplacian\",\"nu\":1e-6}", "fluids[0].xsph=0.05"];

/// The schemes, for cases that compare them only.
const SCHEMES: &[Variant] =
    &[Variant { name: "default", overrides: &[] }, Variant { name: "dfsph", overrides: &[DFSPH] }];

/// The module's accuracy cases.
pub const CASES: &[Case] = &[
    Case {
        name: "hydrostatic",
        module: "fluid",
        reference: "docs/validation/cases.md §1: a column at rest, p = rho0 g (H - y) (Adami, Hu & Adams 2012)",
        preset: "hydrostatic",
        primary_error: "pressure_l2",
        spacings: (&[0.05, 0.0375, 0.025], &[0.05, 0.0375, 0.025, 0.01875]),
        checked_at: Some(0.025),
        bounds: &[("pressure_l2", 0.02), ("mean_density_deviation", 0.01)],
        variants: &HYDROSTATIC_VARIANTS,
        measure: hydrostatic_case,
    },
    Case {
        name: "dam_break",
        module: "fluid",
        reference: "docs/validation/cases.md §2: surge front against Koshizuka & Oka (1996) and Martin & Moyce (1952)",
        preset: "dam_break",
        primary_error: "front_rms",
        spacings: (&[A / 8.0, A / 12.0, A / 16.0], &[A / 12.0, A / 16.0, A / 22.0, A / 28.0]),
        checked_at: Some(A / 8.0),
        bounds: &[("front_max_t2_5", 0.35)],
        variants: &DAM_BREAK_VARIANTS,
        measure: dam_break_case,
    },
    Case {
        name: "poiseuille",
        module: "fluid",
        reference: "docs/validation/cases.md §3: start-up flow between plates, periodic along them (Morris, Fox & Zhu 1997)",
        preset: "poiseuille",
        primary_error: "velocity_l2_steady",
        spacings: (&[0.1, 1.0 / 15.0, 0.05], &[0.1, 1.0 / 15.0, 0.05, 1.0 / 30.0]),
        checked_at: Some(1.0 / 15.0),
        // Walls mirror the fluid's velocity (no slip on the plates themselves) and the
        // Laplacian carries its lattice normalisation: measured 1.4 %, 0.62 % and 0.36 %
        // from coarse to fine at steady state, 0.36 % at t = 0.1 s.
        bounds: &[("velocity_l2_steady", 0.01), ("velocity_l2_t0_1", 0.01), ("velocity_l2_t0_5", 0.01)],
        variants: SCHEMES,
        measure: poiseuille_case,
    },
    Case {
        name: "taylor_green",
        module: "fluid",
        reference: "docs/validation/cases.md §4: Taylor-Green vortices at Re = 100, decaying as exp(-8 pi^2 t / Re)",
        preset: "taylor_green",
        primary_error: "decay_rate_error",
        spacings: (&[1.0 / 40.0], &[1.0 / 40.0, 1.0 / 60.0, 1.0 / 80.0]),
        checked_at: Some(1.0 / 40.0),
        bounds: &[("decay_rate_error", 0.02)],
        variants: &[
            Variant { name: "default", overrides: &[] },
            Variant { name: "wcsph", overrides: &TAYLOR_GREEN_WCSPH },
        ],
        measure: taylor_green_case,
    },
];

/// The velocity across the channel against Morris et al.'s series at t = 0.1, 0.2
/// and 0.5 s (L^2 / nu = 1 s) and at t = 1 s, where every transient mode has decayed
/// below 1e-4 of the flow (the steady state).
fn poiseuille_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (l, nu, force) = POISEUILLE;
    let (l, nu, force) = (f64::from(l), f64::from(nu), f64::from(force));
    let times =
        [("velocity_l2_t0_1", 0.1), ("velocity_l2_t0_2", 0.2), ("velocity_l2_t0_5", 0.5), ("velocity_l2_steady", 1.0)];
    let mut errors = Vec::new();
    let mut wall = 0.0;
    for (name, t) in times {
        let (w, halted) = run_probed(sim, t, t, |_| {});
        wall += w;
        if halted.is_some() {
            return (wall, halted, errors);
        }
        errors.push((name, poiseuille::l2_error(&sim.read(&["velocity"]), sim.time(), force, nu, l)));
    }
    (wall, None, errors)
}

/// Runs to t = 2 s (1.6 e-folding times at Re = 100: the speed falls to 21 %),
/// fits the decay rate to the root-mean-square speed sampled every 0.02 s, and
/// compares the velocity field at the end with the exact one.
fn taylor_green_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (l, u, nu) = TAYLOR_GREEN;
    let tg = TaylorGreen { amplitude: u, wavelength: l };
    let b = taylor_green::decay_rate(f64::from(l), f64::from(nu));
    let mut samples = Vec::new();
    let (wall, halted) =
        run_probed(sim, 2.0, 0.02, |s| samples.push((s.time(), taylor_green::rms_speed(&s.read(&["velocity"])))));
    let rate = taylor_green::fitted_rate(&samples).unwrap_or(f64::NAN);
    let p = sim.read(&["velocity"]);
    let (l1, linf) = taylor_green::velocity_errors(&p, sim.time(), tg, f64::from(nu));
    let exact_rms = f64::from(u) * (b * sim.time()).exp() / 2f64.sqrt();
    let errors = vec![
        ("decay_rate_error", ((rate - b) / b).abs()),
        ("speed_error_t2", (taylor_green::rms_speed(&p) / exact_rms - 1.0).abs()),
        ("velocity_l1_t2", l1),
        ("velocity_linf_t2", linf),
    ];
    (wall, halted, errors)
}

/// Settles for the preset's damped 0.5 s, runs undamped to 1 s, then compares
/// with `rho0 g (H - y)` for H = 0.9 m (Adami et al. 2012).
fn hydrostatic_case(sim: &mut Simulation, spacing: f64) -> Measured {
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
fn dam_break_case(sim: &mut Simulation, spacing: f64) -> Measured {
    let g = 9.81;
    let t_scale = (2.0 * g / A).sqrt();
    let mut history = Vec::new();
    let (wall, halted) = run_probed(sim, dam_break::seconds(3.1, g, A), 0.005, |s| {
        history.push((s.time() * t_scale, dam_break::front(&s.read(&[]).positions, 0.0, spacing, A)));
    });
    let reference = dam_break::reference(dam_break::KOSHIZUKA_OKA);
    let e3 = dam_break::compare(&history, &reference, 3.0);
    let e25 = dam_break::compare(&history, &reference, 2.5);
    let errors =
        vec![("front_rms", e3.rms), ("front_max", e3.max), ("front_bias", e3.bias), ("front_max_t2_5", e25.max)];
    (wall, halted, errors)
}

/// The dam break at spacing a/10 (CI) and a/16 (`--full`).
const BATTERY_SPACING: (f64, f64) = (A / 10.0, A / 16.0);

/// The stability battery: the dam break preset made stiff or extreme.
pub const STABILITY: &[StabilityCase] = &[
    StabilityCase {
        name: "stiff_pressure_10x",
        what: "WCSPH with the speed of sound 10x the usual choice (mach_factor 100)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &[WCSPH, "solver.mach_factor=100"],
        until: (0.03, 0.2),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "stiff_pressure_100x",
        what: "WCSPH with the speed of sound 100x the usual choice (mach_factor 1000)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &[WCSPH, "solver.mach_factor=1000"],
        until: (0.003, 0.02),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "fixed_dt_far_above_cfl",
        what: "fixed dt = 10 ms, about 20x the stable limit (must be sub-stepped)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &["solver.time_step={\"mode\":\"fixed\",\"dt\":0.01}"],
        until: (0.1, 0.5),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "stiff_viscosity",
        what: "Laplacian viscosity nu = 5 m^2/s (viscous step limit dominates)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &["fluids[0].viscosity={\"model\":\"laplacian\",\"nu\":5}"],
        until: (0.02, 0.1),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "overlapping_start",
        what: "two fluid blocks overlapping at the start (density 2x rest where they overlap)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &[
            "fluids[0].blocks=[{\"min\":[0,0,0],\"max\":[0.5,1,0.25]},{\"min\":[0.25,0.5,0],\"max\":[0.75,1.1,0.25]}]",
        ],
        until: (0.1, 0.5),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "high_speed_drop",
        what: "a block thrown down at 20 m/s onto the floor",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &["fluids[0].blocks=[{\"min\":[0.5,0.5,0],\"max\":[1,1,0.25],\"velocity\":[0,-20,0]}]"],
        until: (0.05, 0.3),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "near_zero_gravity",
        what: "gravity 1e-4 m/s^2 (speed of sound derived from a tiny fall speed)",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &["gravity=[0,-1e-4,0]"],
        until: (0.2, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "large_gravity_100g",
        what: "gravity 100 g = 981 m/s^2",
        preset: "dam_break",
        spacing: BATTERY_SPACING,
        overrides: &["gravity=[0,-981,0]"],
        until: (0.01, 0.05),
        expect: Expect::Finish,
    },
];
