//! The one-phase Stefan problem (docs/validation/cases.md section 7): a solid at its
//! melting point fills `x > 0`, the wall at `x = 0` is held at `T_w > T_m` from
//! `t = 0`, and the melt front advances as `s(t) = 2 lambda sqrt(alpha t)`, where
//! `lambda exp(lambda^2) erf(lambda) = St / sqrt(pi)` and `St = c (T_w - T_m) / L`
//! (Carslaw & Jaeger 1959, section 11.2). The preset `stefan` and the case
//! `stefan` that measures the front and the energy balance.

use super::cases::erf;
use super::presets::{fluid, heat, scene, wall_box};
use super::spec::{Melting, ThermalFluid};
use crate::Simulation;
use crate::scene::{Axis, Boundary, BoxRegion, Face, Scene};
use crate::validation::cases::Measured;
use crate::validation::run_probed;
use serde_json::json;

/// Melting point (K).
pub const MELTING_POINT: f32 = 273.15;
/// The wall's temperature (K): 10 K above the melting point.
pub const WALL: f32 = 283.15;
/// Conductivity (W/(m K)), density (kg/m^3) and heat capacity (J/(kg K)) of both
/// phases: diffusivity 1e-4 m^2/s, so the front crosses centimetres in seconds.
pub const PROPERTIES: (f32, f32, f32) = (100.0, 1000.0, 1000.0);
/// Latent heat (J/kg): a Stefan number of 0.5.
pub const LATENT: f32 = 2e4;
/// The slab's length (m) along x and its periodic section (m).
pub const SIZE: (f32, f32) = (0.04, 0.008);
/// The times (s) the front is compared at (1.4 to 2.8 cm from the wall).
pub const TIMES: [f64; 4] = [2.25, 4.0, 6.25, 9.0];

/// The preset: 2 mm particles (20 along x, 320 in all).
pub fn stefan() -> Scene {
    let (k, rho, c) = PROPERTIES;
    let (l, w) = SIZE;
    let phase = |temperature, melting| ThermalFluid {
        conductivity: k,
        heat_capacity: c,
        expansion: 0.0,
        temperature,
        viscosity: None,
        melting,
    };
    let melting = Melting { temperature: MELTING_POINT, latent_heat: LATENT, into: "liquid".into() };
    let heat = heat(
        vec![phase(MELTING_POINT, Some(melting)), phase(MELTING_POINT, None)],
        vec![wall_box([-1.0, -1.0, -1.0], [0.0, 1.0, 1.0], WALL)],
    );
    let none = json!({ "model": "none" });
    let mut liquid = fluid("liquid", rho, none.clone(), [0.0; 3], [0.0; 3]);
    liquid["blocks"] = json!([]);
    let mut s = scene(
        "stefan",
        0.002,
        vec![fluid("solid", rho, none, [0.0; 3], [l, w, w]), liquid],
        vec![Boundary::Box {
            min: [0.0; 3],
            max: [l, w, w],
            open: vec![Face::MinusY, Face::PlusY, Face::MinusZ, Face::PlusZ],
            layers: 2,
        }],
        heat,
    );
    s.gravity = [0.0; 3];
    s.domain = Some(BoxRegion { min: [-0.01, 0.0, 0.0], max: [l + 0.01, w, w] });
    s.periodic = vec![Axis::Y, Axis::Z];
    s.solver.speed_of_sound = Some(0.1);
    s
}

/// `lambda` of Stefan number `st`: the root of `lambda exp(lambda^2) erf(lambda)
/// = st / sqrt(pi)` by bisection (the left side rises from 0).
pub fn lambda(st: f64) -> f64 {
    let target = st / std::f64::consts::PI.sqrt();
    let f = |x: f64| x * (x * x).exp() * erf(x) - target;
    let (mut lo, mut hi) = (0.0, 4.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// The reference front (m) at `t` (s).
pub fn front(t: f64) -> f64 {
    let (k, rho, c) = PROPERTIES;
    let alpha = f64::from(k) / (f64::from(rho) * f64::from(c));
    let st = f64::from(c) * f64::from(WALL - MELTING_POINT) / f64::from(LATENT);
    2.0 * lambda(st) * (alpha * t).sqrt()
}

/// The simulated front (m): the melted volume over the section, `sum beta d^3 / w^2`
/// (a mushy particle counts by its liquid fraction).
pub fn melted_depth(sim: &Simulation, spacing: f64) -> f64 {
    let p = sim.read(&["liquid_fraction"]);
    let beta = p.channel("liquid_fraction").and_then(|b| b.as_scalars()).expect("a scene that melts");
    let w = f64::from(SIZE.1);
    beta.iter().map(|&b| f64::from(b)).sum::<f64>() * spacing.powi(3) / (w * w)
}

/// Runs to the last of [`TIMES`], comparing the front at each: the largest
/// relative error, the last one, and the front (mm) there; and the energy
/// balance at each: the heat the wall gave (`heat.heat_in`, summed apart) against
/// the sensible and latent heat the slab gained (`heat.total_heat` since the
/// start), the largest relative difference.
pub fn case(sim: &mut Simulation, spacing: f64) -> Measured {
    let measure = |s: &Simulation, name: &str| s.measures().into_iter().find(|m| m.name == name).map(|m| m.value);
    let start = measure(sim, "heat.total_heat").unwrap_or(f64::NAN);
    let (mut worst, mut balance) = (0.0f64, 0.0f64);
    let mut next = 0;
    let (wall, halted) = run_probed(sim, TIMES[TIMES.len() - 1], 0.0, |s| {
        if next < TIMES.len() && s.time() >= TIMES[next] {
            let (got, want) = (melted_depth(s, spacing), front(s.time()));
            worst = worst.max((got - want).abs() / want);
            let gained = measure(s, "heat.total_heat").unwrap_or(f64::NAN) - start;
            let given = measure(s, "heat.heat_in").unwrap_or(f64::NAN);
            balance = balance.max((gained - given).abs() / given);
            next += 1;
        }
    });
    let t = sim.time();
    let (got, want) = (melted_depth(sim, spacing), front(t));
    let errors = vec![
        ("front_error", worst),
        ("front_error_last", (got - want).abs() / want),
        ("front_mm", 1e3 * got),
        ("front_reference_mm", 1e3 * want),
        ("energy_balance", balance),
    ];
    (wall, halted, errors)
}

#[cfg(test)]
mod tests {
    #[test]
    fn lambda_solves_its_equation() {
        // St = 0.5: lambda = 0.46479 (0.46479 e^0.21603 erf(0.46479) = 0.28209 = 0.5 / sqrt(pi)).
        assert!((super::lambda(0.5) - 0.46479).abs() < 1e-5, "{}", super::lambda(0.5));
    }
}
