//! The heat module's validation cases (conduction against docs/validation/cases.md §5, the
//! two-layer rest state at density ratios of 10 and 100, de Vahl Davis' heated
//! cavity at Ra = 1e4 and, in `--full`, 1e5, and the channel whose viscosity follows
//! its temperature) and its stability battery (temperature jumps, a very conductive
//! fluid, a large density ratio, a steep viscosity law).

use super::HeatConsts;
use super::presets::{CAVITY_L, CAVITY_T, CHANNEL_T, CONDUCTION_ALPHA, CONDUCTION_L, CONDUCTION_T};
use crate::Simulation;
use crate::validation::cases::{Case, Measured, Variant};
use crate::validation::poiseuille::profile_l2_error;
use crate::validation::run_probed;
use crate::validation::stability::{Expect, StabilityCase};

/// The two-layer cases' spacings (m), quick and full.
const LAYERS_SPACINGS: (&[f64], &[f64]) = (&[0.0125, 0.01], &[0.01, 0.0075, 0.005]);

/// The two-layer cases' bounds: the largest speed 1 s after the damping stops, in
/// units of sqrt(g H), and how far the light fluid's mean height may move (m).
const LAYERS_BOUNDS: &[(&str, f64)] = &[("spurious_speed", 1e-3), ("light_height_drift_m", 0.005)];

/// The module's accuracy cases.
pub const CASES: &[Case] = &[
    Case {
        name: "conduction",
        module: "heat",
        reference: "docs/validation/cases.md §5: two half-spaces in contact, T = (T1 + T2)/2 + (T2 - T1)/2 erf(x / (2 sqrt(alpha t)))",
        preset: "conduction",
        primary_error: "temperature_l2",
        spacings: (&[0.002, 0.0016, 0.001], &[0.002, 0.0016, 0.001, 0.0008]),
        checked_at: Some(0.002),
        bounds: &[("temperature_l2", 0.01)],
        variants: &[
            Variant { name: "default", overrides: &[] },
            Variant { name: "mueller_kernels", overrides: &["solver.kernel=mueller"] },
        ],
        measure: conduction_case,
    },
    Case {
        name: "stefan",
        module: "heat",
        reference: "docs/validation/cases.md §7: one-phase Stefan problem, melt front s(t) = 2 lambda sqrt(alpha t), lambda exp(lambda^2) erf(lambda) = St / sqrt(pi), St = 0.5; energy balance: heat in through the wall = sensible + latent heat stored",
        preset: "stefan",
        primary_error: "front_error",
        spacings: (&[0.002, 0.0013333, 0.001], &[0.002, 0.0013333, 0.001, 0.0005]),
        checked_at: Some(0.0013333),
        bounds: &[("front_error", 0.05), ("energy_balance", 1e-4)],
        variants: &[Variant { name: "default", overrides: &[] }],
        measure: super::stefan::case,
    },
    Case {
        name: "layers_at_rest",
        module: "heat",
        reference: "two fluids at rest, light over heavy: spurious speed after settling, in units of sqrt(g H)",
        preset: "layers",
        primary_error: "spurious_speed",
        spacings: LAYERS_SPACINGS,
        checked_at: Some(0.0125),
        bounds: LAYERS_BOUNDS,
        variants: &[
            Variant { name: "ratio_10", overrides: &[] },
            // What the background pressure buys: the lattice keeps rearranging.
            Variant {
                name: "no_background",
                overrides: &[r#"fluids[0].eos={"kind":"tait"}"#, r#"fluids[1].eos={"kind":"tait"}"#],
            },
            // The control: one fluid (both layers at 1000 kg/m^3).
            Variant { name: "one_fluid", overrides: &["fluids[1].rest_density=1000"] },
        ],
        measure: layers_case,
    },
    Case {
        name: "layers_at_rest_ratio_100",
        module: "heat",
        reference: "two fluids at rest, one of 10 kg/m^3 over water: spurious speed after settling, in units of sqrt(g H)",
        preset: "layers",
        primary_error: "spurious_speed",
        spacings: LAYERS_SPACINGS,
        checked_at: Some(0.0125),
        bounds: LAYERS_BOUNDS,
        variants: &[
            // The light fluid made as stiff as water: a linear law with k = 100 c^2
            // (c = 19.8 m/s, the preset's: ten times the fall speed over the tank's
            // 0.2 m), so both have rho0 c^2 = 3.9e5 Pa and share the preset's
            // background pressure of 1e4 Pa (a Tait fluid of 10 kg/m^3, with 3.9e3 Pa,
            // could not take it); its own speed of sound, 10 c, sets its artificial
            // viscosity and density diffusion.
            Variant {
                name: "equal_stiffness",
                overrides: &[
                    "fluids[1].rest_density=10",
                    r#"fluids[1].eos={"kind":"linear","stiffness":39240,"background":10000}"#,
                ],
            },
        ],
        measure: layers_case,
    },
    Case {
        name: "heated_cavity",
        module: "heat",
        reference: "de Vahl Davis (1983), Ra = 1e4, Pr = 0.71: mean Nusselt number 2.243, u_max = 16.178 alpha/L on the vertical midline, v_max = 19.617 alpha/L on the horizontal one",
        preset: "heated_cavity",
        primary_error: "nusselt_error",
        // 10, 15, 20 particles across (the finest 90 s on 2 cores); 25 in `--full`.
        spacings: (&[0.005, 0.0033333, 0.0025], &[0.005, 0.0033333, 0.0025, 0.002]),
        checked_at: Some(0.0025),
        bounds: &[("nusselt_error", 0.05), ("u_max_error", 0.05), ("v_max_error", 0.05)],
        variants: &[
            Variant { name: "default", overrides: &[] },
            // What the transport velocity buys: without it the flow runs 12 to 15 % slow.
            Variant { name: "no_transport_velocity", overrides: &[NO_TRANSPORT] },
        ],
        measure: |sim, spacing| cavity_case(sim, spacing, &RA_1E4),
    },
    Case {
        name: "heated_cavity_ra1e5",
        module: "heat",
        reference: "de Vahl Davis (1983), Ra = 1e5, Pr = 0.71: mean Nusselt number 4.519, u_max = 34.73 alpha/L on the vertical midline, v_max = 68.59 alpha/L on the horizontal one",
        preset: "heated_cavity",
        primary_error: "nusselt_error",
        // Thinner boundary layers: from 20 particles across, in `--full` only.
        spacings: (&[], &[0.0025, 0.002, 0.0016667]),
        checked_at: None,
        bounds: &[("nusselt_error", 0.05)],
        variants: &[
            Variant { name: "default", overrides: CAVITY_RA_1E5 },
            Variant { name: "no_transport_velocity", overrides: CAVITY_RA_1E5_PLAIN },
        ],
        measure: |sim, spacing| cavity_case(sim, spacing, &RA_1E5),
    },
    Case {
        name: "heated_channel",
        module: "heat",
        reference: "steady channel flow between plates at 280 K and 320 K with mu(T) = 1000 exp(-b (T - 300)) Pa s: \
                    the linear conduction profile, and u(y) = rho F / (int 1/mu) of the stress rho F (y_c - y) over mu, \
                    by quadrature",
        preset: "heated_channel",
        primary_error: "velocity_l2",
        // The conduction limit sets dt (4000 steps at 0.05 m): 20 layers in `--full` only.
        spacings: (&[0.1, 1.0 / 15.0], &[0.1, 1.0 / 15.0, 0.05, 1.0 / 30.0]),
        checked_at: Some(0.1),
        bounds: &[("velocity_l2", 0.03), ("temperature_l2", 0.01)],
        variants: &[
            Variant { name: "implicit", overrides: &[] },
            Variant { name: "explicit", overrides: &[r#"heat.viscous_solver={"method":"explicit"}"#] },
        ],
        measure: channel_case,
    },
];

/// Simulated time (s) of the `heated_channel` case: the slowest thermal and viscous
/// modes decay as `exp(-pi^2 D t / L^2)` with D about 1 m^2/s, 5e-5 of their start by 1 s.
const CHANNEL_T_END: f64 = 1.0;

/// The steady velocity across the `heated_channel` (plates at `y = 0` and `l`,
/// driven by `rho_f` = rho F, Pa/m) whose viscosity at height y is `mu(y)`: the
/// stress is `rho F (y_c - y)`, zero at the height `y_c` that makes the velocity
/// vanish on both plates, `y_c = int y / mu / int 1 / mu`; then
/// `u(y) = int_0^y rho F (y_c - s) / mu(s) ds`. Trapezoidal rule on `cells` cells;
/// returns `u` at `y = k l / cells`.
pub fn channel_profile(mu: impl Fn(f64) -> f64, rho_f: f64, l: f64, cells: usize) -> Vec<f64> {
    let dy = l / cells as f64;
    let inv: Vec<f64> = (0..=cells).map(|k| 1.0 / mu(k as f64 * dy)).collect();
    let integral = |f: &dyn Fn(usize) -> f64| (1..=cells).map(|k| 0.5 * dy * (f(k - 1) + f(k))).sum::<f64>();
    let y_c = integral(&|k| k as f64 * dy * inv[k]) / integral(&|k| inv[k]);
    let mut u = vec![0.0; cells + 1];
    for k in 1..=cells {
        let g = |k: usize| rho_f * (y_c - k as f64 * dy) * inv[k];
        u[k] = u[k - 1] + 0.5 * dy * (g(k - 1) + g(k));
    }
    u
}

/// Runs to [`CHANNEL_T_END`], then compares the temperatures with the linear profile
/// between the plates (L2 over the plates' difference) and the velocities with
/// [`channel_profile`] of the fluid's law along that profile.
fn channel_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let (wall, halted) = run_probed(sim, CHANNEL_T_END, CHANNEL_T_END, |_| {});
    if halted.is_some() {
        return (wall, halted, Vec::new());
    }
    let rho = sim.model().materials.get(0).rest_density;
    let (rho_f, l) = (f64::from(rho) * f64::from(sim.scene().gravity[0]), 1.0);
    let (cold, hot) = (f64::from(CHANNEL_T.0), f64::from(CHANNEL_T.1));
    let linear = |y: f64| cold + (hot - cold) * (y / l).clamp(0.0, 1.0);
    let law = sim.model().consts::<HeatConsts>().viscosity[0];
    let cells = 4000;
    let u = channel_profile(|y| f64::from(law.viscosity(linear(y) as f32)), rho_f, l, cells);
    let at = |y: f64| {
        let f = (y / l).clamp(0.0, 1.0) * cells as f64;
        let k = (f.floor() as usize).min(cells - 1);
        u[k] + (u[k + 1] - u[k]) * (f - k as f64)
    };
    let p = sim.read(&["velocity", "temperature"]);
    let t = p.channel("temperature").and_then(|t| t.as_scalars()).expect("temperatures requested");
    let sq: f64 = p.positions.iter().zip(t).map(|(x, &t)| (f64::from(t) - linear(f64::from(x[1]))).powi(2)).sum();
    let temperature_l2 = (sq / t.len().max(1) as f64).sqrt() / (hot - cold);
    let errors = vec![("velocity_l2", profile_l2_error(&p, at)), ("temperature_l2", temperature_l2)];
    (wall, None, errors)
}

/// Overrides taking the `heated_cavity` (Ra = 1e4) to Ra = 1e5: its viscosity
/// `CAVITY_NU` and its conductivity `rho c nu / 0.71` divided by sqrt(10), so Pr
/// stays 0.71 (a unit test checks the figures).
const CAVITY_RA_1E5: &[&str] = &[RA_1E5_VISCOSITY, RA_1E5_CONDUCTIVITY, RA_1E5_SOUND, RA_1E5_BACKGROUND];
const RA_1E5_VISCOSITY: &str = r#"fluids[0].viscosity={"model":"laplacian","nu":3.16228e-5}"#;
const RA_1E5_CONDUCTIVITY: &str = "heat.fluids[0].conductivity=44.5392";
/// At Ra = 1e5 the flow is two to three and a half times faster than at 1e4: the
/// speed of sound stays 2 m/s (its runs' Mach number below 0.1), twice the preset's
/// [`super::presets::CAVITY_C`], with the transport velocity's background pressure `rho0 c^2`.
const RA_1E5_SOUND: &str = "solver.speed_of_sound=2";
const RA_1E5_BACKGROUND: &str = r#"solver.transport_velocity={"background":4000}"#;

/// The cavity without the transport velocity its preset uses, at Ra = 1e5.
const CAVITY_RA_1E5_PLAIN: &[&str] = &[RA_1E5_VISCOSITY, RA_1E5_CONDUCTIVITY, RA_1E5_SOUND, NO_TRANSPORT];
const NO_TRANSPORT: &str = "solver.transport_velocity=null";

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

/// Settles under the preset's damping (3 s), runs undamped for 1 s more, then reports
/// the largest speed over `sqrt(g H)` (H = 0.2 m, the tank's fill) and how far the
/// light fluid's mean height moved from its start at 0.15 m.
fn layers_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let end = super::presets::LAYERS_SETTLE + 1.0;
    let (wall, halted) = run_probed(sim, end, end, |_| {});
    let p = sim.read(&["velocity", "material"]);
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    let m = p.channel("material").and_then(|m| m.as_exact()).expect("two materials");
    let vmax = v.iter().map(|v| f64::from(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).fold(0.0, f64::max);
    let light: Vec<f64> = p.positions.iter().zip(m).filter(|&(_, &m)| m == 1).map(|(x, _)| f64::from(x[1])).collect();
    let mean = light.iter().sum::<f64>() / light.len().max(1) as f64;
    let errors = vec![("spurious_speed", vmax / (9.81f64 * 0.2).sqrt()), ("light_height_drift_m", (mean - 0.15).abs())];
    (wall, halted, errors)
}

/// A heated cavity's reference (de Vahl Davis 1983, table I) and how long to run it.
#[derive(Debug)]
pub struct CavityRun {
    /// Rayleigh number.
    pub rayleigh: f64,
    /// Mean Nusselt number.
    pub nusselt: f64,
    /// The largest `u` on the vertical midline (alpha / L).
    pub u_max: f64,
    /// The largest `v` on the horizontal midline (alpha / L).
    pub v_max: f64,
    /// The run's end (s); its figures are averaged over samples every
    /// [`CAVITY_SAMPLE`] s from `average_from` (s) on: a particle field's
    /// instantaneous heat flux fluctuates by a few per cent.
    pub t_end: f64,
    /// Start of the average (s).
    pub average_from: f64,
}

/// Ra = 1e4: from rest the flow and Nusselt number settle within about 3 s (a sixth
/// of the diffusion time `L^2 / alpha`).
const RA_1E4: CavityRun =
    CavityRun { rayleigh: 1e4, nusselt: 2.243, u_max: 16.178, v_max: 19.617, t_end: 12.0, average_from: 4.0 };
/// Ra = 1e5: the diffusion time is sqrt(10) times longer; the Nusselt number settles
/// by about 5 s (measured: frames from 5 s to 18 s within 4.56 to 4.68).
const RA_1E5: CavityRun =
    CavityRun { rayleigh: 1e5, nusselt: 4.519, u_max: 34.73, v_max: 68.59, t_end: 16.0, average_from: 5.0 };
const CAVITY_SAMPLE: f64 = 0.25;

/// The cavity's mean Nusselt number from the volume-averaged horizontal heat flux,
/// `Nu = 1 + L <u (T - T0)> / (alpha dT)` (in steady state the flux through every
/// vertical plane is the walls'; the conductive part averages to `alpha dT / L`),
/// and the largest speeds on the midlines, `u` along `x = L/2` and `v` along
/// `y = L/2`, in units of `alpha / L`: each midline is the particles within one
/// spacing of it, averaged in bins one spacing long.
fn cavity_figures(sim: &Simulation, spacing: f64) -> [f64; 3] {
    let p = sim.read(&["velocity", "temperature"]);
    let heat = super::section(sim.scene());
    let thermal = &heat.fluids[0];
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocity requested");
    let t = p.channel("temperature").and_then(|t| t.as_scalars()).expect("temperature requested");
    let (l, dt) = (f64::from(CAVITY_L), f64::from(CAVITY_T.0 - CAVITY_T.1));
    let t0 = 0.5 * f64::from(CAVITY_T.0 + CAVITY_T.1);
    let alpha = f64::from(thermal.conductivity)
        / (f64::from(sim.model().materials.get(0).rest_density) * f64::from(thermal.heat_capacity));
    let flux = v.iter().zip(t).map(|(v, &t)| f64::from(v[0]) * (f64::from(t) - t0)).sum::<f64>();
    let nusselt = 1.0 + l * flux / (v.len().max(1) as f64 * alpha * dt);
    let bins = (l / spacing).round() as usize;
    let midline_max = |across: usize, along: usize, component: usize| {
        let mut sum = vec![(0.0f64, 0u32); bins];
        for (x, v) in p.positions.iter().zip(v) {
            if (f64::from(x[across]) - 0.5 * l).abs() < spacing {
                let k = ((f64::from(x[along]) / l * bins as f64) as usize).min(bins - 1);
                sum[k] = (sum[k].0 + f64::from(v[component]), sum[k].1 + 1);
            }
        }
        sum.iter().filter(|b| b.1 > 0).map(|b| (b.0 / f64::from(b.1)).abs()).fold(0.0, f64::max) * l / alpha
    };
    [nusselt, midline_max(0, 1, 0), midline_max(1, 0, 1)]
}

fn cavity_case(sim: &mut Simulation, spacing: f64, reference: &CavityRun) -> Measured {
    let (mut sum, mut n) = ([0.0f64; 3], 0u32);
    let (wall, halted) = run_probed(sim, reference.t_end, CAVITY_SAMPLE, |s| {
        if s.time() >= reference.average_from {
            for (a, b) in sum.iter_mut().zip(cavity_figures(s, spacing)) {
                *a += b;
            }
            n += 1;
        }
    });
    let [nusselt, u_max, v_max] = sum.map(|s| s / f64::from(n.max(1)));
    let errors = vec![
        ("nusselt_error", (nusselt / reference.nusselt - 1.0).abs()),
        ("u_max_error", (u_max / reference.u_max - 1.0).abs()),
        ("v_max_error", (v_max / reference.v_max - 1.0).abs()),
        ("nusselt", nusselt),
    ];
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
        name: "viscosity_ratio_1e4",
        what: "the heated channel with a viscosity falling 1e4-fold from the cold plate to the hot one \
               (2e4 to 2 Pa s), implicit viscosity",
        preset: "heated_channel",
        spacing: (0.1, 0.05),
        overrides: &[
            r#"heat.fluids[0].viscosity={"law":"exponential","mu_ref":200,"t_ref":300,"b":0.2303}"#,
            "heat.max_viscosity=1e5",
        ],
        until: (0.2, 1.0),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "density_ratio_1000",
        what: "a fluid of 1 kg/m^3 over one of 1000 kg/m^3",
        preset: "layers",
        spacing: BATTERY_SPACING,
        // Without the preset's background pressure, which a fluid this light cannot take.
        overrides: &[
            "fluids[1].rest_density=1",
            r#"fluids[0].eos={"kind":"tait"}"#,
            r#"fluids[1].eos={"kind":"tait"}"#,
        ],
        until: (0.2, 1.0),
        expect: Expect::FinishOrHalt,
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::from_preset;

    /// `Ra = g beta dT L^3 / (nu alpha)` and `Pr = nu / alpha` of the cavity with `overrides`.
    fn rayleigh_prandtl(overrides: &[&str]) -> (f64, f64) {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        let scene = from_preset("heated_cavity", &overrides).expect("the cavity builds");
        let heat = super::super::section(&scene);
        let thermal = &heat.fluids[0];
        // The fluid module's section, read as the document has it.
        let fluid = &scene.section::<serde_json::Value>("fluids").expect("fluids")[0];
        let nu = fluid["viscosity"]["nu"].as_f64().expect("a Laplacian viscosity") as f32;
        let rest_density = fluid["rest_density"].as_f64().expect("a rest density");
        let alpha = f64::from(thermal.conductivity) / (rest_density * f64::from(thermal.heat_capacity));
        let g = f64::from(heat.buoyancy_gravity.expect("its own g")[1]).abs();
        let dt = f64::from(CAVITY_T.0 - CAVITY_T.1);
        let ra = g * f64::from(thermal.expansion) * dt * f64::from(CAVITY_L).powi(3) / (f64::from(nu) * alpha);
        (ra, f64::from(nu) / alpha)
    }

    #[test]
    fn the_cavity_cases_run_at_their_rayleigh_number() {
        for (overrides, run) in [(&[][..], &RA_1E4), (CAVITY_RA_1E5, &RA_1E5)] {
            let (ra, pr) = rayleigh_prandtl(overrides);
            assert!((ra / run.rayleigh - 1.0).abs() < 1e-4, "Ra {ra} for {}", run.rayleigh);
            assert!((pr / 0.71 - 1.0).abs() < 1e-4, "Pr {pr}");
        }
    }
}
