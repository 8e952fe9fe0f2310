//! The snow module's built-in scenes: three channel flows of VALIDATION.md §6
//! (non-Newtonian Poiseuille flow between plates 1 m apart, periodic along them,
//! the fluid preset `poiseuille` with another rheology). Their viscosities are
//! about 1000 Pa s at the walls (kinematic 1 m^2/s, as the Newtonian preset's), so
//! each settles within a second and is bound by the viscous step, not by sound.

use super::spec::{Rheology, Snow};
use crate::modules::Preset;
use crate::scene::{Scene, Viscosity};

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "power_law_channel",
        about: "Shear-thickening power-law fluid (n = 1.5) driven between plates (VALIDATION.md §6).",
        scene: power_law_channel,
    },
    Preset {
        name: "bingham_channel",
        about: "Bingham plastic between plates: an unsheared plug 0.3 m wide in the middle (VALIDATION.md §6).",
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
    let mut s = crate::modules::fluid::presets::poiseuille();
    s.name = name.into();
    s.modules = vec!["fluid".into(), "snow".into()];
    s.fluids[0].viscosity = Viscosity::None;
    s.snow = Some(Snow { fluids: vec![rheology], max_viscosity });
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
