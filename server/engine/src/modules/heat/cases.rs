//! The heat module's validation cases (VALIDATION.md §5 and the two-layer rest
//! state) and its stability battery (temperature jumps, a very conductive fluid,
//! a large density ratio).

use super::presets::{CONDUCTION_ALPHA, CONDUCTION_L, CONDUCTION_T};
use crate::Simulation;
use crate::validation::cases::{Case, Measured, Variant};
use crate::validation::run_probed;
use crate::validation::stability::{Expect, StabilityCase};

/// The module's accuracy cases.
pub const CASES: &[Case] = &[
    Case {
        name: "conduction",
        module: "heat",
        reference: "VALIDATION.md §5: two half-spaces in contact, T = (T1 + T2)/2 + (T2 - T1)/2 erf(x / (2 sqrt(alpha t)))",
        preset: "conduction",
        primary_error: "temperature_l2",
        spacings: (&[0.002, 0.0016, 0.001], &[0.002, 0.0016, 0.001, 0.0008]),
        bounds: &[("temperature_l2", 0.01)],
        variants: &[
            Variant { name: "default", overrides: &[] },
            Variant { name: "mueller_kernels", overrides: &["solver.kernel=mueller"] },
        ],
        measure: conduction_case,
    },
    Case {
        name: "layers_at_rest",
        module: "heat",
        reference: "two fluids at rest, light over heavy: spurious speed after settling, in units of sqrt(g H)",
        preset: "layers",
        primary_error: "spurious_speed",
        spacings: (&[0.0125, 0.01], &[0.01, 0.0075, 0.005]),
        bounds: &[("light_height_drift_m", 0.005)],
        variants: &[
            Variant { name: "ratio_10", overrides: &[] },
            Variant { name: "ratio_100", overrides: &["fluids[1].rest_density=10"] },
        ],
        measure: layers_case,
    },
];

/// Simulated time (s) of the conduction case: the diffusion length `2 sqrt(alpha t)`
/// grows to L/8.
const CONDUCTION_T_END: f64 = 0.16;

/// The periodic slab's exact temperature at `x` (m), time `t` (s): the erf solution
/// of each interface, summed over periodic images (those further than two periods
/// contribute nothing in f64).
pub fn conduction_reference(x: f64, t: f64) -> f64 {
    let (t1, t2) = (f64::from(CONDUCTION_T.0), f64::from(CONDUCTION_T.1));
    let l = f64::from(CONDUCTION_L);
    let s = 2.0 * (f64::from(CONDUCTION_ALPHA) * t).sqrt();
    let images: f64 = (-2..=2)
        .map(|n| {
            let shift = f64::from(n) * l;
            erf((x - 0.5 * l - shift) / s) - erf((x - l - shift) / s)
        })
        .sum();
    t1 + 0.5 * (t2 - t1) * images
}

/// The error function, |error| < 1.2e-7 (Numerical Recipes' `erfc` by Chebyshev fit).
pub fn erf(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98 + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let erfc = t * poly.exp();
    if x >= 0.0 { 1.0 - erfc } else { erfc - 1.0 }
}

/// L2 (root mean square) and Linf of the temperature against the erf solution at the
/// scene's time, relative to the jump `T2 - T1`.
pub fn conduction_errors(sim: &Simulation) -> (f64, f64) {
    let p = sim.read(&["temperature"]);
    let t = p.channel("temperature").and_then(|t| t.as_scalars()).expect("temperature requested");
    let jump = f64::from(CONDUCTION_T.1 - CONDUCTION_T.0);
    let (mut sq, mut max) = (0.0f64, 0.0f64);
    for (x, &ti) in p.positions.iter().zip(t) {
        let e = (f64::from(ti) - conduction_reference(f64::from(x[0]), sim.time())).abs() / jump;
        sq += e * e;
        max = max.max(e);
    }
    ((sq / t.len().max(1) as f64).sqrt(), max)
}

fn conduction_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let mut early = None;
    let (wall, halted) = run_probed(sim, CONDUCTION_T_END, CONDUCTION_T_END / 4.0, |s| {
        if early.is_none() && s.time() >= CONDUCTION_T_END / 4.0 {
            early = Some(conduction_errors(s));
        }
    });
    let (l2, linf) = conduction_errors(sim);
    let (l2_early, linf_early) = early.unwrap_or((f64::NAN, f64::NAN));
    let errors = vec![
        ("temperature_l2", l2),
        ("temperature_linf", linf),
        ("temperature_l2_quarter_time", l2_early),
        ("temperature_linf_quarter_time", linf_early),
    ];
    (wall, halted, errors)
}

/// Settles under the preset's damping (0.5 s), runs undamped to 1 s, then reports
/// the largest speed over `sqrt(g H)` (H = 0.2 m, the tank's fill) and how far the
/// light fluid's mean height moved from its start at 0.15 m.
fn layers_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (wall, halted) = run_probed(sim, 1.0, 1.0, |_| {});
    let p = sim.read(&["velocity", "material"]);
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    let m = p.channel("material").and_then(|m| m.as_exact()).expect("two materials");
    let vmax = v.iter().map(|v| f64::from(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).fold(0.0, f64::max);
    let light: Vec<f64> = p.positions.iter().zip(m).filter(|&(_, &m)| m == 1).map(|(x, _)| f64::from(x[1])).collect();
    let mean = light.iter().sum::<f64>() / light.len().max(1) as f64;
    let errors = vec![("spurious_speed", vmax / (9.81f64 * 0.2).sqrt()), ("light_height_drift_m", (mean - 0.15).abs())];
    (wall, halted, errors)
}

/// Spacing (m) of the battery's `convection` runs in quick and full mode.
const BATTERY_SPACING: (f64, f64) = (0.01, 0.0075);

/// The stability battery.
pub const STABILITY: &[StabilityCase] = &[
    StabilityCase {
        name: "temperature_jump_100k",
        what: "floor 100 K hotter than the water",
        preset: "convection",
        spacing: BATTERY_SPACING,
        overrides: &["heat.walls[0].temperature=410", "heat.fluids[0].temperature=310"],
        until: (0.2, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "temperature_jump_1000k",
        what: "floor 1000 K hotter than the water (buoyancy beta dT = 2)",
        preset: "convection",
        spacing: BATTERY_SPACING,
        overrides: &["heat.walls[0].temperature=1310", "heat.fluids[0].temperature=310"],
        until: (0.2, 1.0),
        expect: Expect::FinishOrHalt,
    },
    StabilityCase {
        name: "conductivity_1e4_water",
        what: "conductivity 6000 W/(m K), 1e4 x water's",
        preset: "convection",
        spacing: BATTERY_SPACING,
        overrides: &["heat.fluids[0].conductivity=6000"],
        until: (0.05, 0.2),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "diffusion_limited",
        what: "conductivity 1e6 W/(m K): the diffusion limit (4e-5 s at 1 cm) sets dt",
        preset: "convection",
        spacing: BATTERY_SPACING,
        overrides: &["heat.fluids[0].conductivity=1e6"],
        until: (0.01, 0.05),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "density_ratio_1000",
        what: "a fluid of 1 kg/m^3 over one of 1000 kg/m^3",
        preset: "layers",
        spacing: BATTERY_SPACING,
        overrides: &["fluids[1].rest_density=1"],
        until: (0.2, 1.0),
        expect: Expect::FinishOrHalt,
    },
];
