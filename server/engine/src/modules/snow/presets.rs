//! The snow module's built-in scenes: the avalanche, and three channel flows of
//! docs/validation/cases.md §6 (non-Newtonian Poiseuille flow between plates 1 m apart,
//! periodic along them, the fluid preset `poiseuille` with another rheology). The
//! channels' viscosities are about 1000 Pa s at the walls (kinematic 1 m^2/s, as
//! the Newtonian preset's), so each settles within a second and is bound by the
//! viscous step, not by sound.

use super::spec::{Rheology, Snow};
use crate::module::Preset;
use crate::scene::{Boundary, Face, Scene, Solver};
use crate::terrain::spec::{Heights, Slope, Terrain};
use crate::viscosity::{ViscousSolver, WallShear};
use serde_json::json;

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "avalanche",
        about: "A wedge of snow (Cross model) released on a 35 degree mountain side runs out into the valley.",
        scene: avalanche,
    },
    Preset {
        name: "avalanche_thesis",
        about: "The avalanche in the snow thesis's configuration: its Cross law as printed (viscosity rising with shear), XSPH 0.5, leap-frog on WCSPH.",
        scene: avalanche_thesis,
    },
    Preset {
        name: "power_law_channel",
        about: "Shear-thickening power-law fluid (n = 1.5) driven between plates (docs/validation/cases.md §6).",
        scene: power_law_channel,
    },
    Preset {
        name: "bingham_channel",
        about: "Bingham plastic between plates: an unsheared plug 0.3 m wide in the middle (docs/validation/cases.md §6).",
        scene: bingham_channel,
    },
    Preset {
        name: "cross_channel",
        about: "Cross-model fluid (the snow model) between plates, thinning from 3000 to 300 Pa s.",
        scene: cross_channel,
    },
];

/// Density (kg/m^3), driving force (m/s^2) and plate distance (m) of the channels.
pub const CHANNEL: (f32, f32, f32) = (1000.0, 0.1, 1.0);

fn channel(name: &str, rheology: Rheology, max_viscosity: f32) -> Scene {
    let mut s = crate::scene::presets::get("poiseuille")
        .expect("the fluid module's channel")
        .with("fluids[0].viscosity", json!({ "model": "none" }));
    s.name = name.into();
    s.modules = vec!["fluid".into(), "snow".into()];
    let snow =
        Snow { fluids: vec![rheology], max_viscosity, walls: WallShear::NoSlip, solver: ViscousSolver::default() };
    s.sections.set(super::SECTION, &snow);
    s
}

/// `mu = K g^0.5`, K = 4472 Pa s^1.5: 1000 Pa s at the walls' shear rate 0.05 1/s,
/// falling to 0 on the centre line; peak velocity 0.015 m/s. Clamped at 1100 Pa s,
/// above any viscosity the flow reaches (the clamp sets the viscous step).
pub fn power_law_channel() -> Scene {
    channel("power_law_channel", Rheology::PowerLaw { k: 4472.0, n: 1.5 }, 1100.0)
}

/// tau_0 = 15 Pa (a plug of half-width tau_0 / (rho F) = 0.15 m), mu_p = 1000 Pa s,
/// regularised with m = 600 s, so the plug at rest reaches mu_p + tau_0 m = 1e4 Pa s
/// (the clamp).
pub fn bingham_channel() -> Scene {
    channel("bingham_channel", Rheology::Bingham { yield_stress: 15.0, mu_p: 1000.0, m: 600.0 }, 1e4)
}

/// mu_0 = 3000, mu_inf = 300 Pa s, K = 20 s, n = 1: halfway at 0.05 1/s, about
/// the shear rate near the walls.
pub fn cross_channel() -> Scene {
    channel("cross_channel", Rheology::Cross { mu_0: 3000.0, mu_inf: 300.0, k: 20.0, n: 1.0 }, 3000.0)
}

/// Extent of the avalanche's ground along x and z (m), its top height (m) and slope
/// angle (degrees).
pub const AVALANCHE: (f32, f32, f32, f32) = (10.0, 0.8, 2.0, 35.0);

/// A chute-sized avalanche: a mountain side falling 2 m at 35 degrees into a flat
/// valley 10 m from the top, 0.8 m wide between side walls, with Coulomb friction 0.5
/// (rest below 27 degrees: the snow slides down the slope and stops in the valley) and walls
/// that exert no viscous shear (`snow.walls = "slip"`: friction alone holds the base). The snow is
/// the block `x` 0.1 to 1.0 m below 1.95 m, less what lies under the ground: a wedge
/// 0.6 m thick at its foot. Snow of 300 kg/m^3 is a Cross fluid (mu_0 = 200 Pa s at
/// rest, thinning to 5 Pa s, K = 1 s), the law of the avalanche model the module
/// follows; 14,726 particles at 2.5 cm. `snow.front` and `snow.runout` report
/// where its foremost particle is. DFSPH with the implicit viscosity, chosen by
/// measurement (docs/snow.md): it steps at the flow's limit, about 20 times
/// WCSPH's acoustic step.
pub fn avalanche() -> Scene {
    let (length, width, top, angle) = AVALANCHE;
    let ground = Terrain {
        min: [0.0, 0.0],
        max: [length, width],
        heights: Heights::Slope(Slope { top, valley: 0.0, angle, foot: 0.2, ripple: 0.05, wavelength: width }),
        friction: 0.5,
        layers: 2,
    };
    let mut s = Scene {
        name: "avalanche".into(),
        modules: vec!["fluid".into(), "snow".into()],
        particle_spacing: 0.025,
        gravity: [0.0, -9.81, 0.0],
        boundaries: vec![
            Boundary::Box {
                min: [0.0, -0.5, 0.0],
                max: [length, top + 1.0, width],
                open: vec![Face::MinusY, Face::PlusY],
                layers: 1,
            },
            Boundary::Terrain(ground),
        ],
        domain: None,
        periodic: Vec::new(),
        solver: Solver { method: "dfsph".into(), ..Solver::default() },
        guard: Default::default(),
        sections: Default::default(),
    }
    .with(
        "fluids",
        json!([{
            "name": "snow",
            "rest_density": 300.0,
            "viscosity": { "model": "none" },
            "look": "snow",
            "blocks": [{ "min": [0.1, 0.0, 0.0], "max": [1.0, top - 0.05, width] }],
        }]),
    );
    let snow = Snow {
        fluids: vec![Rheology::Cross { mu_0: 200.0, mu_inf: 5.0, k: 1.0, n: 1.0 }],
        max_viscosity: 200.0,
        walls: WallShear::Slip,
        solver: ViscousSolver::default(),
    };
    s.sections.set(super::SECTION, &snow);
    s
}

/// The [`avalanche`] in the configuration of the snow thesis (the seeds' `004`,
/// section 3): its Cross law with the parameters of its fig. 3.9 as printed,
/// `mu_inf = 200`, `mu_0 = 1` Pa s, `K = 300` s, `n = 1` (eq. 3.29), so the viscosity
/// rises from 1 Pa s at rest to 200 as the snow is sheared, where Floe's thins from 200
/// to 5; XSPH with epsilon 0.5 (its eq. 3.62); leap-frog time integration on WCSPH, the
/// scheme of its real-time solver. Everything else (ground, walls, the snow's block and
/// density, the clamp at 200 Pa s) is [`avalanche`]'s, so the two compare
/// (docs/snow.md, "The snow thesis's avalanche").
pub fn avalanche_thesis() -> Scene {
    let mut s = avalanche().with("fluids[0].xsph", json!(0.5));
    s.name = "avalanche_thesis".into();
    s.solver.method = "wcsph".into();
    s.solver.integrator = crate::scene::Integrator::Leapfrog;
    let mut snow: Snow = s.section(super::SECTION).expect("the avalanche's snow");
    snow.fluids = vec![Rheology::Cross { mu_0: 1.0, mu_inf: 200.0, k: 300.0, n: 1.0 }];
    s.sections.set(super::SECTION, &snow);
    s
}
