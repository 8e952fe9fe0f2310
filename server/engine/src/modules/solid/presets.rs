//! The solid module's built-in scenes.

use crate::module::Preset;
use crate::scene::{Boundary, Face, Scene, Solver};
use serde_json::json;

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "elastic_drop",
        about: "A jelly cube 20 cm wide dropped on the floor from 0.3 m: it bounces, wobbles and settles, keeping its shape.",
        scene: elastic_drop,
    },
    Preset {
        name: "bunny",
        about: "An elastic Stanford bunny 32 cm long (about 6,500 particles at 1 cm) dropped on the floor from 10 cm: it bounces, wobbles and settles.",
        scene: bunny,
    },
    Preset {
        name: "floating_blocks",
        about: "Two elastic blocks, one half as dense as water and one twice, dropped into a tank of water: one floats, one sinks.",
        scene: floating_blocks,
    },
];

/// Side of the jelly cube (m) and the height of its bottom at the start (m).
pub const DROP: (f32, f32) = (0.2, 0.3);

/// A jelly cube of 1000 particles at 2 cm (1000 kg/m^3, no viscosity) dropped
/// from 0.3 m into a closed box 0.6 m wide; shape matching with alpha 0.5 and
/// three iterations a step holds it together.
pub fn elastic_drop() -> Scene {
    let (side, drop) = DROP;
    let (lo, hi) = (0.3 - 0.5 * side, 0.3 + 0.5 * side);
    open_box("elastic_drop", 0.02, [0.6, 0.8, 0.6], (2.0f32 * 9.81 * drop).sqrt())
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

/// A tank 0.6 m square with water 0.3 m deep, and two elastic cubes 12 cm wide
/// dropped from 0.1 m above it: `light` (500 kg/m^3) floats half out of the water,
/// `heavy` (2000 kg/m^3) sinks to the floor. About 14,000 particles at 2 cm.
pub fn floating_blocks() -> Scene {
    let cube = |x: f32| json!([{ "min": [x, 0.4, 0.24], "max": [x + 0.12, 0.52, 0.36] }]);
    let body = |name: &str, density: f32, x: f32| {
        json!({ "name": name, "rest_density": density, "look": "ice",
                "viscosity": { "model": "artificial", "alpha": 0.05 }, "blocks": cube(x) })
    };
    open_box("floating_blocks", 0.02, [0.6, 0.8, 0.6], (2.0f32 * 9.81 * 0.5).sqrt())
        .with(
            "fluids",
            json!([
                { "name": "water", "rest_density": 1000.0, "viscosity": { "model": "artificial", "alpha": 0.02 },
                  "blocks": [{ "min": [0.0, 0.0, 0.0], "max": [0.6, 0.3, 0.6] }] },
                body("light", 500.0, 0.1),
                body("heavy", 2000.0, 0.38),
            ]),
        )
        .with(
            "solid",
            json!({ "bodies": [{ "fluid": "light" }, { "fluid": "heavy" }], "stiffness": 0.5, "iterations": 3 }),
        )
}

/// The box the bunny fills (m): the built-in mesh's proportions, 32 cm long,
/// its lowest point 10 cm above the floor of [`bunny`]'s box.
pub const BUNNY: ([f32; 3], [f32; 3]) = ([0.24, 0.1, 0.18], [0.56, 0.412, 0.4235]);

/// The first thesis's bunny: the built-in Stanford bunny filled at 1 cm
/// (about 6,500 particles; its solver table also used 2106 and 889, at 1.46 and
/// 1.94 cm), 1000 kg/m^3, dropped from 10 cm in a closed box 0.8 x 0.8 x 0.6 m;
/// alpha 0.5, three Jacobi iterations a step.
pub fn bunny() -> Scene {
    let (lo, hi) = BUNNY;
    // The landing speed (1.4 m/s) and the ears flapping faster.
    open_box("bunny", 0.01, [0.8, 0.8, 0.6], 3.0)
        .with(
            "fluids",
            json!([{
                "name": "bunny",
                "rest_density": 1000.0,
                "viscosity": { "model": "artificial", "alpha": 0.05 },
                "look": "ice",
                "blocks": [{ "min": lo, "max": hi, "mesh": { "builtin": "bunny" } }],
            }]),
        )
        .with("solid", json!({ "bodies": [{ "fluid": "bunny" }], "stiffness": 0.5, "iterations": 3 }))
}

/// A scene of fluid and elastic bodies in a box of walls from the origin to
/// `max` (m), open at the top, under gravity; `speed` is the fastest a particle
/// is expected to move (m/s).
fn open_box(name: &str, spacing: f32, max: [f32; 3], speed: f32) -> Scene {
    Scene {
        name: name.into(),
        modules: vec!["fluid".into(), super::MODULE.id.into()],
        particle_spacing: spacing,
        gravity: [0.0, -9.81, 0.0],
        boundaries: vec![Boundary::Box { min: [0.0; 3], max, open: vec![Face::PlusY], layers: 2 }],
        domain: None,
        periodic: Vec::new(),
        solver: Solver { expected_max_speed: Some(speed), ..Solver::default() },
        guard: Default::default(),
        sections: Default::default(),
    }
}
