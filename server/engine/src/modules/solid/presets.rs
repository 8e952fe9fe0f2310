//! The solid module's built-in scenes.

use crate::module::Preset;
use crate::scene::{Boundary, Face, Scene, Solver};
use serde_json::json;

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[Preset {
    name: "elastic_drop",
    about: "A jelly cube 20 cm wide dropped on the floor from 0.3 m: it bounces, wobbles and settles, keeping its shape.",
    scene: elastic_drop,
}];

/// Side of the jelly cube (m) and the height of its bottom at the start (m).
pub const DROP: (f32, f32) = (0.2, 0.3);

/// A jelly cube of 1000 particles at 2 cm (1000 kg/m^3, no viscosity) dropped
/// from 0.3 m into a closed box 0.6 m wide; shape matching with alpha 0.5 and
/// three iterations a step holds it together.
pub fn elastic_drop() -> Scene {
    let (side, drop) = DROP;
    let (lo, hi) = (0.3 - 0.5 * side, 0.3 + 0.5 * side);
    Scene {
        name: "elastic_drop".into(),
        modules: vec!["fluid".into(), super::MODULE.id.into()],
        particle_spacing: 0.02,
        gravity: [0.0, -9.81, 0.0],
        boundaries: vec![Boundary::Box { min: [0.0; 3], max: [0.6, 0.8, 0.6], open: vec![Face::PlusY], layers: 2 }],
        domain: None,
        periodic: Vec::new(),
        solver: Solver { expected_max_speed: Some((2.0f32 * 9.81 * drop).sqrt()), ..Solver::default() },
        guard: Default::default(),
        sections: Default::default(),
    }
    .with(
        "fluids",
        json!([{
            "name": "jelly",
            "rest_density": 1000.0,
            "viscosity": { "model": "artificial", "alpha": 0.05 },
            "look": "ice",
            "blocks": [{ "min": [lo, drop, lo], "max": [hi, drop + side, hi] }],
        }]),
    )
    .with("solid", json!({ "bodies": [{ "fluid": "jelly" }], "stiffness": 0.5, "iterations": 3 }))
}
