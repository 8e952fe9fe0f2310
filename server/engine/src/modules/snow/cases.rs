//! The snow module's validation cases (docs/validation/cases.md §6) and stability battery.

use super::SnowConsts;
use super::channel::{self, l2_error};
use super::presets::CHANNEL;
use super::rheology::Kind;
use crate::Simulation;
use crate::validation::cases::{Case, Measured, Variant};
use crate::validation::run_probed;
use crate::validation::stability::{Expect, StabilityCase};

/// Spacings of the channel cases (m): 10 to 20 layers across the quick runs.
const SPACINGS: (&[f64], &[f64]) = (&[0.1, 1.0 / 15.0, 0.05], &[0.1, 1.0 / 15.0, 0.05, 1.0 / 30.0]);

/// The variants every case runs: the implicit solve (the default) and the explicit
/// viscous force (bound by the explicit viscous step), with the default scheme
/// (`floe validate --set 'solver.method="dfsph"'` runs them with DFSPH).
const DEFAULT: &[Variant] =
    &[Variant { name: "implicit", overrides: &[] }, Variant { name: "explicit", overrides: &[EXPLICIT] }];

/// The explicit viscous force.
const EXPLICIT: &str = "snow.solver={\"method\":\"explicit\"}";

/// The module's accuracy cases.
pub const CASES: &[Case] = &[
    Case {
        name: "power_law_channel",
        module: "snow",
        reference: "docs/validation/cases.md §6: steady power-law channel flow, closed form",
        preset: "power_law_channel",
        primary_error: "velocity_l2",
        spacings: SPACINGS,
        checked_at: Some(0.1),
        bounds: &[("velocity_l2", 0.03)],
        variants: DEFAULT,
        measure: channel_case,
    },
    Case {
        name: "bingham_channel",
        module: "snow",
        reference: "docs/validation/cases.md §6: steady Bingham channel flow with its plug, closed form",
        preset: "bingham_channel",
        primary_error: "velocity_l2",
        spacings: SPACINGS,
        checked_at: Some(0.1),
        bounds: &[("velocity_l2", 0.03)],
        variants: DEFAULT,
        measure: channel_case,
    },
    Case {
        name: "cross_channel",
        module: "snow",
        reference: "docs/validation/cases.md §6: steady Cross-model channel flow against the 1D grid solution of the same ODE",
        preset: "cross_channel",
        primary_error: "velocity_l2",
        spacings: SPACINGS,
        checked_at: Some(0.1),
        bounds: &[("velocity_l2", 0.03)],
        variants: DEFAULT,
        measure: channel_case,
    },
];

/// Simulated time (s) of the channel cases: measured, the layer velocities change by
/// less than 0.1 % between 0.75 s and 1.5 s.
pub const CHANNEL_T_END: f64 = 1.0;

/// Runs to [`CHANNEL_T_END`] and compares the velocities with the steady profile of
/// the scene's law: the closed form for a power law and a Bingham plastic (with
/// the plug width's error), the 1D grid solution otherwise.
fn channel_case(sim: &mut Simulation, spacing: f64) -> Measured {
    let (wall, halted) = run_probed(sim, CHANNEL_T_END, CHANNEL_T_END, |_| {});
    if halted.is_some() {
        return (wall, halted, Vec::new());
    }
    let law = sim.model().consts::<SnowConsts>().laws[0];
    let (rho, _, l) = CHANNEL;
    let rho_f = f64::from(rho) * f64::from(sim.scene().gravity[0]);
    let l = f64::from(l);
    let p = sim.read(&["velocity"]);
    let [a, b, ..] = law.p.map(f64::from);
    let mut errors = match law.kind {
        Kind::PowerLaw => vec![("velocity_l2", l2_error(&p, |y| channel::power_law(y, rho_f, a, b, l)))],
        Kind::Bingham => {
            let reference = |y| channel::bingham(y, rho_f, a, b, l);
            let ideal: Vec<f64> =
                (0..(l / spacing).round() as usize).map(|k| reference((k as f64 + 0.5) * spacing)).collect();
            let (w, w_ref) = (
                channel::plug_half_width(&channel::layers(&p, spacing, l), spacing, l),
                channel::plug_half_width(&ideal, spacing, l),
            );
            // The regularised law the scene runs (m = 600 s, clamped) flows otherwise than
            // the ideal plastic near the yield surface: its own steady profile tells the
            // discretisation's error from the model's.
            let regularised = channel::steady_profile(&law, rho_f, l, 2000);
            vec![
                ("velocity_l2", l2_error(&p, reference)),
                ("plug_width_error", (w - w_ref).abs() / w_ref),
                ("velocity_l2_regularised", l2_error(&p, |y| regularised.at(y))),
            ]
        }
        _ => {
            let profile = channel::steady_profile(&law, rho_f, l, 2000);
            vec![("velocity_l2", l2_error(&p, |y| profile.at(y)))]
        }
    };
    errors.push(("max_viscosity_pa_s", f64::from(law.max)));
    (wall, None, errors)
}

/// The stability battery: stiff viscosities under the explicit viscous limit and
/// with the implicit solve, a yield stress that must hold, a hard impact.
pub const STABILITY: &[StabilityCase] = &[
    StabilityCase {
        name: "cross_ratio_1e4",
        what: "Cross model with mu_0 / mu_inf = 1e4 (3e4 over 3 Pa s), explicit viscosity at its viscous limit",
        preset: "cross_channel",
        spacing: (0.1, 0.05),
        overrides: &["snow.fluids[0].mu_0=3e4", "snow.fluids[0].mu_inf=3", "snow.max_viscosity=3e4", EXPLICIT],
        until: (0.05, 0.5),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "cross_ratio_1e6",
        what: "Cross model with mu_0 / mu_inf = 1e6 (3e5 over 0.3 Pa s), explicit viscosity at its viscous limit",
        preset: "cross_channel",
        spacing: (0.1, 0.05),
        overrides: &["snow.fluids[0].mu_0=3e5", "snow.fluids[0].mu_inf=0.3", "snow.max_viscosity=3e5", EXPLICIT],
        until: (0.005, 0.05),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "cross_ratio_1e6_implicit",
        what: "Cross model with mu_0 / mu_inf = 1e6, implicit viscosity at the pressure-limited dt",
        preset: "cross_channel",
        spacing: (0.1, 0.05),
        overrides: &[
            "snow.fluids[0].mu_0=3e5",
            "snow.fluids[0].mu_inf=0.3",
            "snow.max_viscosity=3e5",
            "snow.solver={\"method\":\"implicit\"}",
        ],
        until: (0.5, 1.5),
        expect: Expect::Finish,
    },
    StabilityCase {
        name: "bingham_slab_holds",
        what: "the avalanche's slab as a Bingham plastic (yield stress 1e4 Pa, ten times the basal shear stress) on the \
               35-degree slope without Coulomb friction, no-slip bed, implicit viscosity: it must stay put",
        preset: "avalanche",
        spacing: (0.05, 0.025),
        overrides: &[
            "snow.fluids[0]={\"model\":\"bingham\",\"yield_stress\":1e4,\"mu_p\":1,\"m\":100}",
            "snow.max_viscosity=1e6",
            "snow.walls=\"no_slip\"",
            "boundaries[1].friction=0",
            "snow.solver={\"method\":\"implicit\"}",
        ],
        until: (0.2, 1.0),
        expect: Expect::StayPut(0.5),
    },
    StabilityCase {
        name: "avalanche_dropped_from_high",
        what: "the avalanche's snow dropped 2.5 m onto the mountain side (about 7 m/s at impact)",
        preset: "avalanche",
        spacing: (0.05, 0.025),
        overrides: &["fluids[0].blocks[0]={\"min\":[0.1,4.0,0.0],\"max\":[1.0,4.5,0.8]}"],
        until: (1.0, 3.0),
        expect: Expect::Finish,
    },
];
