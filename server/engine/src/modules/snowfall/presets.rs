//! The snowfall module's built-in scenes: a valley under heavy snow, and the roof
//! of docs/validation/cases.md §9 that its cases run.

use super::spec::{Area, Intensity, Object, Release, Snowfall};
use crate::module::Preset;
use crate::scene::{Boundary, BoxRegion, Face, Scene, Solver, TimeStep};
use crate::terrain::spec::{Heights, Slope, Terrain};
use serde_json::json;

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "snowfall",
        about: "Heavy snow in the wind over a valley with a house, a car and trees: the cover grows, the lee of the house stays bare.",
        scene: snowfall,
    },
    Preset {
        name: "snowfall_then_avalanche",
        about: "Snow falls on a 35 degree mountain side for 20 s, then the cover on the slope is released as avalanche snow and runs into the valley.",
        scene: snowfall_then_avalanche,
    },
    Preset {
        name: "snow_roof",
        about: "Snow falling on a roof 2 m above flat ground (docs/validation/cases.md §9: flux, shelter, accounting).",
        scene: snow_roof,
    },
];

fn scene(name: &str, spacing: f32, domain: BoxRegion, boundaries: Vec<Boundary>, snowfall: &Snowfall) -> Scene {
    let mut s = Scene {
        name: name.into(),
        modules: vec![super::MODULE.id.into()],
        particle_spacing: spacing,
        gravity: [0.0, -9.81, 0.0],
        boundaries,
        domain: Some(domain),
        periodic: Vec::new(),
        // No SPH particles: the flakes' own limit (half a cell a step) sets the step,
        // up to 0.1 s (the scheme asks for a speed of sound, which then limits nothing).
        solver: Solver {
            time_step: TimeStep::Adaptive { cfl: 0.5, min: 1e-7, max: 0.1 },
            speed_of_sound: Some(10.0),
            ..Solver::default()
        },
        guard: Default::default(),
        sections: Default::default(),
    };
    s.sections.set(super::SECTION, snowfall);
    s
}

/// A valley 24 m x 16 m: a mountain side falling 6 m at 30 degrees along x into a
/// flat floor with a house (4 m x 3 m x 5 m), a car and three trees, under 10
/// flakes per m^2 per s in a 1.5 m/s wind along x, gusting by 30 %. The cover
/// grows at 5 mm/s on open ground (a time-lapse: `depth_per_hour` 18 m); the house
/// shelters about `3 m x 1.5 / 1` = 4.5 m of ground downwind.
pub fn snowfall() -> Scene {
    let (length, width) = (24.0, 16.0);
    let valley = Terrain {
        min: [0.0, 0.0],
        max: [length, width],
        heights: Heights::Slope(Slope {
            top: 6.0,
            valley: 0.0,
            angle: 30.0,
            foot: 1.0,
            ripple: 0.5,
            wavelength: width,
        }),
        friction: 0.5,
        layers: 1,
    };
    let tree = |x: f32, z: f32| Object::Cylinder { centre: [x, z], radius: 0.4, bottom: 0.0, top: 5.0 };
    let fall = Snowfall {
        area: Area { min: [0.0, 0.0], max: [length, width] },
        height: 12.0,
        floor: 0.0,
        intensity: Intensity::Rate { flakes_per_m2_s: 10.0 },
        max_intensity: None,
        depth_per_hour: 18.0,
        terminal_speed: 1.0,
        wind: [1.5, 0.0],
        gusts: 0.3,
        gust_period: 6.0,
        turbulence: None,
        flutter: 1.0,
        cell: None,
        coverage_cone: 25.0,
        release: None,
        objects: vec![
            Object::Box { min: [13.0, 0.0, 5.0], max: [17.0, 3.0, 10.0] },
            Object::Box { min: [20.0, 0.0, 11.0], max: [21.8, 1.4, 15.0] },
            tree(12.0, 3.0),
            tree(12.5, 13.0),
            tree(22.0, 3.5),
        ],
    };
    let domain = BoxRegion { min: [0.0, -1.0, 0.0], max: [length, 13.0, width] };
    scene("snowfall", 0.25, domain, vec![Boundary::Terrain(valley)], &fall)
}

/// Height of the roof's underside (m), its span along x and the emission height.
pub const ROOF: (f32, [f32; 2], f32) = (2.0, [6.0, 8.0], 4.0);

/// Flat ground 16 m x 4 m under a roof 0.1 m thick from x = 6 to 8 m, 2 m up,
/// spanning the whole width; 200 flakes per m^2 per s from 4 m, no wind, no
/// flutter, no gusts. The cases add wind (`snowfall.wind`) and flutter.
pub fn snow_roof() -> Scene {
    let (h, [x0, x1], height) = ROOF;
    let fall = Snowfall {
        area: Area { min: [0.0, 0.0], max: [16.0, 4.0] },
        height,
        floor: 0.0,
        intensity: Intensity::Rate { flakes_per_m2_s: 200.0 },
        max_intensity: None,
        depth_per_hour: 0.05,
        terminal_speed: 1.0,
        wind: [0.0, 0.0],
        gusts: 0.0,
        gust_period: 5.0,
        turbulence: None,
        flutter: 0.0,
        cell: None,
        coverage_cone: 25.0,
        release: None,
        objects: vec![Object::Box { min: [x0, h, -1.0], max: [x1, h + 0.1, 5.0] }],
    };
    let domain = BoxRegion { min: [0.0, -1.0, 0.0], max: [16.0, 5.0, 4.0] };
    scene("snow_roof", 0.25, domain, Vec::new(), &fall)
}

/// Extent of the mountain side along x and z (m), its top (m), slope (degrees)
/// and the release's time (s).
pub const MOUNTAIN: (f32, f32, f32, f32, f32) = (8.0, 2.0, 3.0, 35.0, 20.0);

/// A mountain side 3 m high at 35 degrees (friction 0.5: snow slides above 27
/// degrees) into a flat valley, 8 m x 2 m between side walls, under 50 flakes per
/// m^2 per s laying 15 mm of snow a second (a time-lapse): at 20 s the cover,
/// about 0.3 m deep, is released where the ground is steeper than 20 degrees as
/// particles of `snow` (200 kg/m^3, the avalanche preset's Cross law) and runs out
/// into the valley, where the cover stays. About 12,000 particles at 5 cm.
pub fn snowfall_then_avalanche() -> Scene {
    let (length, width, top, angle, at) = MOUNTAIN;
    let ground = Terrain {
        min: [0.0, 0.0],
        max: [length, width],
        heights: Heights::Slope(Slope { top, valley: 0.0, angle, foot: 0.2, ripple: 0.05, wavelength: width }),
        friction: 0.5,
        layers: 2,
    };
    let walls = Boundary::Box {
        min: [0.0, -0.5, 0.0],
        max: [length, top + 3.0, width],
        open: vec![Face::MinusY, Face::PlusY],
        layers: 1,
    };
    let fall = Snowfall {
        area: Area { min: [0.0, 0.0], max: [length, width] },
        height: top + 2.0,
        floor: 0.0,
        intensity: Intensity::Rate { flakes_per_m2_s: 600.0 },
        max_intensity: None,
        depth_per_hour: 54.0,
        terminal_speed: 1.0,
        wind: [0.0, 0.0],
        gusts: 0.0,
        gust_period: 5.0,
        turbulence: None,
        flutter: 0.5,
        cell: None,
        coverage_cone: 25.0,
        release: Some(Release { fluid: "snow".into(), at: Some(at), min_slope: 20.0, particles: 20_000 }),
        objects: Vec::new(),
    };
    let domain = BoxRegion { min: [0.0, -0.5, 0.0], max: [length, top + 3.0, width] };
    let mut s = scene("snowfall_then_avalanche", 0.05, domain, vec![walls, Boundary::Terrain(ground)], &fall);
    s.modules = vec!["fluid".into(), "snow".into(), super::MODULE.id.into()];
    // DFSPH, chosen by measurement (docs/snow.md): the released snow steps at the
    // flow's limit. The snow's speed down 3 m would set WCSPH's speed of sound (the
    // fluid has no particles to derive it from until the release).
    s.solver.method = "dfsph".into();
    s.solver.speed_of_sound = None;
    s.solver.expected_max_speed = Some((2.0 * 9.81 * top).sqrt());
    s.with(
        "fluids",
        json!([{
            "name": "snow",
            "rest_density": 200.0,
            "viscosity": { "model": "none" },
            "look": "snow",
            "blocks": [],
        }]),
    )
    .with(
        "snow",
        json!({
            "fluids": [{ "model": "cross", "mu_0": 200.0, "mu_inf": 5.0, "k": 1.0, "n": 1.0 }],
            "max_viscosity": 200.0,
            "walls": "slip",
        }),
    )
}
