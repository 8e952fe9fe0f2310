//! Ice that melts (the solid module with heat's phase change): the conservation
//! case of a melting body in an insulated glass.

use crate::Simulation;
use crate::validation::cases::Measured;
use crate::validation::run_probed;

/// How long the insulated glass runs (s): the cube sinks into the water at
/// 0.06 s and about half of it melts by 1 s.
pub const INSULATED_END: f64 = 1.0;

/// The ice cube at its melting point in the glass, whose walls are all insulated:
/// the total heat (sensible and latent, `heat.total_heat`) must hold, the solid's
/// mass only fall (melt next to ice at the melting point cannot freeze), and the
/// mass of solid and melt together stay the cube's. Reports the largest relative
/// change of the total heat over samples every 10 ms, the largest rise of the
/// solid's mass between samples (kg), the largest relative change of the phases'
/// total mass, and the fraction melted at the end.
pub fn insulated_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let measure =
        |s: &Simulation, name: &str| s.measures().into_iter().find(|m| m.name == name).map_or(f64::NAN, |m| m.value);
    let start = (measure(sim, "heat.total_heat"), measure(sim, "heat.solid_mass") + measure(sim, "heat.melt_mass"));
    let (mut drift, mut rise, mut mass, mut last) = (0.0f64, 0.0f64, 0.0f64, measure(sim, "heat.solid_mass"));
    let (wall, halted) = run_probed(sim, INSULATED_END, 0.01, |s| {
        let solid = measure(s, "heat.solid_mass");
        drift = drift.max((measure(s, "heat.total_heat") - start.0).abs() / start.0);
        mass = mass.max((solid + measure(s, "heat.melt_mass") - start.1).abs() / start.1);
        rise = rise.max(solid - last);
        last = solid;
    });
    let melted = measure(sim, "heat.melt_mass") / start.1;
    (wall, halted, vec![("heat_drift", drift), ("solid_mass_rise_kg", rise), ("mass_error", mass), ("melted", melted)])
}
