//! The heat module's built-in scenes: ordinary [`Scene`] values, so `--set`
//! overrides and `floe schema` apply to them as to files.

use super::spec::{Heat, TemperatureBox, ThermalFluid, ViscosityLaw};
use crate::module::Preset;
use crate::scene::{Axis, Boundary, BoxRegion, Face, Scene, Solver, TimeStep};
use serde_json::{Value, json};

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "conduction",
        about: "Two half-spaces at 280 K and 320 K in contact, at rest, periodic (docs/validation/cases.md §5): 4,096 particles.",
        scene: conduction,
    },
    Preset {
        name: "convection",
        about: "Water in a closed tank over a floor at 330 K under a lid at 290 K: rising plumes (25,600 particles).",
        scene: convection,
    },
    Preset {
        name: "two_fluids",
        about: "Rayleigh-Taylor: a cold fluid three times as dense over a warm light one (25,600 particles).",
        scene: two_fluids,
    },
    Preset {
        name: "heated_cavity",
        about: "Differentially heated square cavity at Ra = 1e4, Pr = 0.71 (de Vahl Davis 1983), a thin periodic slab.",
        scene: heated_cavity,
    },
    Preset {
        name: "heated_channel",
        about: "Channel flow between plates at 280 K and 320 K: the viscosity falls fourfold across it (exponential law).",
        scene: heated_channel,
    },
    Preset {
        name: "stefan",
        about: "The one-phase Stefan problem (docs/validation/cases.md §7): a slab of solid at its melting point melts from a wall 10 K warmer (Stefan number 0.5), 320 particles.",
        scene: super::stefan::stefan,
    },
    Preset {
        name: "layers",
        about: "A light fluid at rest on one ten times as dense, in a closed tank: spurious currents at the interface.",
        scene: layers,
    },
];

/// Temperatures (K) of the two halves of `conduction`.
pub const CONDUCTION_T: (f32, f32) = (280.0, 320.0);
/// Length (m) of the `conduction` slab along x (periodic: two interfaces, at 0 and L/2).
pub const CONDUCTION_L: f32 = 0.064;
/// Thermal diffusivity (m^2/s) of the `conduction` material: k = 100 W/(m K),
/// rho = 1000 kg/m^3, c = 1000 J/(kg K).
pub const CONDUCTION_ALPHA: f32 = 1e-4;

/// A fluid of the `fluids` section (the fluid module's, as the document has it)
/// filling the box `min`-`max` at rest.
pub(super) fn fluid(name: &str, rest_density: f32, viscosity: Value, min: [f32; 3], max: [f32; 3]) -> Value {
    json!({ "name": name, "rest_density": rest_density, "viscosity": viscosity, "blocks": [{ "min": min, "max": max }] })
}

/// A Laplacian viscosity of kinematic viscosity `nu` (m^2/s).
fn laplacian(nu: f32) -> Value {
    json!({ "model": "laplacian", "nu": nu })
}

fn water(temperature: f32, expansion: f32) -> ThermalFluid {
    ThermalFluid { conductivity: 0.6, heat_capacity: 4186.0, expansion, temperature, viscosity: None, melting: None }
}

pub(super) fn heat(fluids: Vec<ThermalFluid>, walls: Vec<TemperatureBox>) -> Heat {
    Heat {
        fluids,
        reference_temperature: 293.15,
        buoyancy_gravity: None,
        regions: Vec::new(),
        walls,
        sources: Vec::new(),
        fluxes: Vec::new(),
        range: [1.0, 1e4],
        max_viscosity: 1e3,
        viscous_solver: Default::default(),
    }
}

pub(super) fn wall_box(min: [f32; 3], max: [f32; 3], temperature: f32) -> TemperatureBox {
    TemperatureBox { min, max, temperature }
}

pub(super) fn scene(name: &str, spacing: f32, fluids: Vec<Value>, boundaries: Vec<Boundary>, heat: Heat) -> Scene {
    let mut s = Scene {
        name: name.into(),
        modules: vec!["fluid".into(), "heat".into()],
        particle_spacing: spacing,
        gravity: [0.0, -9.81, 0.0],
        boundaries,
        domain: None,
        periodic: Vec::new(),
        solver: Solver::default(),
        guard: Default::default(),
        sections: Default::default(),
    }
    .with("fluids", Value::Array(fluids));
    s.sections.set(super::SECTION, &heat);
    s
}

/// A slab 64 mm long, 8 mm square in section, periodic on every axis, with no
/// gravity: x < L/2 at 280 K, x > L/2 at 320 K. The material's diffusivity is
/// 1e-4 m^2/s so a run is limited by conduction, not sound (c = 0.1 m/s).
pub fn conduction() -> Scene {
    let (l, w) = (CONDUCTION_L, 0.008);
    let mut heat = heat(
        vec![ThermalFluid {
            conductivity: 100.0,
            heat_capacity: 1000.0,
            expansion: 0.0,
            temperature: CONDUCTION_T.0,
            viscosity: None,
            melting: None,
        }],
        Vec::new(),
    );
    heat.regions.push(TemperatureBox { min: [0.5 * l, 0.0, 0.0], max: [l, w, w], temperature: CONDUCTION_T.1 });
    let mut s = scene(
        "conduction",
        0.001,
        vec![fluid("conductor", 1000.0, json!({ "model": "none" }), [0.0; 3], [l, w, w])],
        Vec::new(),
        heat,
    );
    s.gravity = [0.0; 3];
    s.domain = Some(BoxRegion { min: [0.0; 3], max: [l, w, w] });
    s.periodic = vec![Axis::X, Axis::Y, Axis::Z];
    s.solver.speed_of_sound = Some(0.1);
    s
}

/// A tank 0.4 x 0.2 x 0.04 m full of water with an exaggerated expansion
/// (2e-3 1/K), the floor held at 330 K and the lid at 290 K; side walls insulated.
pub fn convection() -> Scene {
    let (lx, ly, lz) = (0.4, 0.2, 0.04);
    let floor = wall_box([-1.0, -1.0, -1.0], [1.0, 0.0, 1.0], 330.0);
    let lid = wall_box([-1.0, ly, -1.0], [1.0, 1.0, 1.0], 290.0);
    scene(
        "convection",
        0.005,
        vec![fluid("water", 1000.0, laplacian(1e-4), [0.0; 3], [lx, ly, lz])],
        vec![Boundary::Box { min: [0.0; 3], max: [lx, ly, lz], open: Vec::new(), layers: 1 }],
        heat(vec![water(310.0, 2e-3)], vec![floor, lid]),
    )
}

/// A tank 0.2 x 0.4 x 0.04 m: a cold fluid of 3000 kg/m^3 over warm water,
/// separated by a flat interface at half height; the heavy one sinks in fingers.
pub fn two_fluids() -> Scene {
    let (lx, ly, lz) = (0.2, 0.4, 0.04);
    let fluids = vec![
        fluid("light", 1000.0, laplacian(1e-4), [0.0; 3], [lx, 0.5 * ly, lz]),
        fluid("heavy", 3000.0, laplacian(1e-4), [0.0, 0.5 * ly, 0.0], [lx, ly, lz]),
    ];
    let mut s = scene(
        "two_fluids",
        0.005,
        fluids,
        vec![Boundary::Box { min: [0.0; 3], max: [lx, ly, lz], open: Vec::new(), layers: 1 }],
        heat(vec![water(320.0, 2.1e-4), ThermalFluid { heat_capacity: 1500.0, ..water(280.0, 1e-4) }], Vec::new()),
    );
    s.solver.speed_of_sound = Some(20.0);
    s
}

/// Side (m) of the `heated_cavity`.
pub const CAVITY_L: f32 = 0.05;
/// Wall temperatures (K) of the `heated_cavity`: hot (left), cold (right).
pub const CAVITY_T: (f32, f32) = (298.0, 288.0);
/// Kinematic viscosity (m^2/s) of the `heated_cavity`'s fluid; its diffusivity is
/// `nu / 0.71` (Pr = 0.71).
pub const CAVITY_NU: f32 = 1e-4;

/// The square cavity of de Vahl Davis (1983), side L = 0.05 m, a slab 2 cm thick
/// (two kernel supports at the coarsest useful spacing, 5 mm), periodic in z: the
/// left wall at 298 K, the right at 288 K, top and bottom insulated;
/// Pr = nu / alpha = 0.71, beta chosen for Ra = g beta dT L^3 / (nu alpha) = 1e4.
/// The cavity is closed and full, so the scene has no gravity and the buoyancy its
/// own g (`heat.buoyancy_gravity`): the pressure is the Boussinesq reduced pressure.
/// The speed of sound, [`CAVITY_C`], is 20 times the flow's largest speed. The
/// transport velocity with Adami et al.'s background pressure `rho0 c^2` keeps the
/// circulating particles evenly spread: without it the flow runs 12 to 15 % slow at every
/// resolution (docs/heat.md).
pub fn heated_cavity() -> Scene {
    let (l, d) = (CAVITY_L, 0.0025);
    let (nu, rho, c) = (CAVITY_NU, 1000.0, 1000.0);
    let alpha = nu / 0.71;
    let dt = CAVITY_T.0 - CAVITY_T.1;
    let beta = 1e4 * nu * alpha / (9.81 * dt * l * l * l);
    let k = alpha * rho * c;
    let hot = wall_box([-1.0, -1.0, -1.0], [0.0, 1.0, 1.0], CAVITY_T.0);
    let cold = wall_box([l, -1.0, -1.0], [1.0, 1.0, 1.0], CAVITY_T.1);
    let t0 = 0.5 * (CAVITY_T.0 + CAVITY_T.1);
    let thermal = ThermalFluid {
        conductivity: k,
        heat_capacity: c,
        expansion: beta,
        temperature: t0,
        viscosity: None,
        melting: None,
    };
    let mut heat = heat(vec![thermal], vec![hot, cold]);
    heat.reference_temperature = t0;
    heat.buoyancy_gravity = Some([0.0, -9.81, 0.0]);
    let depth = 0.02;
    let mut s = scene(
        "heated_cavity",
        d,
        vec![fluid("air-like", rho, laplacian(nu), [0.0; 3], [l, l, depth])],
        vec![Boundary::Box { min: [0.0; 3], max: [l, l, depth], open: vec![Face::MinusZ, Face::PlusZ], layers: 2 }],
        heat,
    );
    s.domain = Some(BoxRegion { min: [-0.01, -0.01, 0.0], max: [l + 0.01, l + 0.01, depth] });
    s.periodic = vec![Axis::Z];
    s.gravity = [0.0; 3];
    s.solver.speed_of_sound = Some(CAVITY_C);
    s.solver = s.solver.with("transport_velocity", json!({ "background": rho * CAVITY_C * CAVITY_C }));
    s
}

/// Speed of sound (m/s) of the `heated_cavity`: 20 times the flow's largest speed
/// at Ra = 1e4 (Mach 0.05), chosen by measurement: half the steps of 2 m/s, with Nu,
/// u_max and v_max within 3.0, 2.8 and 2.0 % at 20 particles across, against 4.6,
/// 1.4 and 1.0 % at 2 m/s (the speeds a little further off, the Nusselt number
/// closer, all within the case's 5 %; docs/heat.md).
pub const CAVITY_C: f32 = 1.0;

/// A tank 0.2 x 0.2 x 0.04 m: a light fluid (100 kg/m^3) on a heavy one
/// (1000 kg/m^3), each 0.1 m deep, at one temperature, settling under damping for
/// 3 s (the lattice the blocks start on rearranges under its own weight for about
/// that long). Its density is integrated (δ-SPH), which starts both layers in
/// hydrostatic balance and keeps each particle's density its own fluid's; both
/// fluids share a background pressure of [`LAYERS_BACKGROUND`], which keeps the
/// lattice from rearranging once settled (docs/heat.md).
pub fn layers() -> Scene {
    let (lx, ly, lz) = (0.2, 0.2, 0.04);
    let fluid = |name, rest_density, min: [f32; 3], max: [f32; 3]| {
        let mut f = fluid(name, rest_density, json!({ "model": "artificial", "alpha": 0.02 }), min, max);
        f["eos"] = json!({ "kind": "tait", "gamma": 7.0, "background": LAYERS_BACKGROUND });
        f
    };
    let fluids = vec![
        fluid("heavy", 1000.0, [0.0; 3], [lx, 0.5 * ly, lz]),
        fluid("light", 100.0, [0.0, 0.5 * ly, 0.0], [lx, ly, lz]),
    ];
    let mut s = scene(
        "layers",
        0.005,
        fluids,
        vec![Boundary::Box { min: [0.0; 3], max: [lx, ly, lz], open: Vec::new(), layers: 1 }],
        heat(vec![water(293.15, 0.0), ThermalFluid { heat_capacity: 1000.0, ..water(293.15, 0.0) }], Vec::new()),
    );
    s.solver.damping = 5.0;
    s.solver.damping_until = LAYERS_SETTLE as f32;
    s.solver = s.solver.with("delta_sph", json!({ "delta": 0.1 }));
    s.solver.time_step = TimeStep::Adaptive { cfl: 0.5, min: 1e-7, max: 5e-3 };
    s
}

/// When the `layers` preset's damping stops (s).
pub const LAYERS_SETTLE: f64 = 3.0;

/// The `layers` preset's background pressure (Pa): 2.5 % of the heavy fluid's
/// `rho0 c^2`, a quarter of the light one's.
pub const LAYERS_BACKGROUND: f32 = 1e4;

/// Wall temperatures (K) of the `heated_channel`: the plate at y = 0, the plate at y = L.
pub const CHANNEL_T: (f32, f32) = (280.0, 320.0);

/// The fluid module's `poiseuille` channel (plates 1 m apart, periodic along them,
/// driven by 0.1 m/s^2 along x) with the plates held at 280 K and 320 K and the
/// viscosity following Reynolds' exponential law, 2000 Pa s at the cold plate to
/// 500 Pa s at the hot one (kinematic 2 to 0.5 m^2/s). The conductivity gives a
/// diffusivity of 1 m^2/s, so the linear temperature profile sets in as fast as the
/// flow (both within about 0.3 s); the fluid starts at 300 K.
pub fn heated_channel() -> Scene {
    let mut s = crate::scene::presets::get("poiseuille")
        .expect("the fluid module's channel")
        .with("fluids[0].viscosity", json!({ "model": "none" }));
    s.name = "heated_channel".into();
    s.modules = vec!["fluid".into(), "heat".into()];
    let (cold, hot) = CHANNEL_T;
    let law = ViscosityLaw::Exponential { mu_ref: 1000.0, t_ref: 300.0, b: 4f32.ln() / (hot - cold) };
    let thermal = ThermalFluid {
        conductivity: 1e6,
        heat_capacity: 1000.0,
        expansion: 0.0,
        temperature: 300.0,
        viscosity: Some(law),
        melting: None,
    };
    let walls =
        vec![wall_box([-1.0, -1.0, -1.0], [2.0, 0.0, 2.0], cold), wall_box([-1.0, 1.0, -1.0], [2.0, 2.0, 2.0], hot)];
    s.sections.set(super::SECTION, &Heat { max_viscosity: 1e4, range: [270.0, 330.0], ..heat(vec![thermal], walls) });
    s
}
