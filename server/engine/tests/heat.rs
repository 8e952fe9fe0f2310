//! The heat module on the CPU: conduction against the erf solution (docs/validation/cases.md
//! §5), heat conserved in an insulated box, a wall's heat flux, walls held at a
//! temperature (on their surface), the
//! temperature guard, and the section's validation.

use floe_engine::Simulation;
use floe_engine::modules::heat::cases::{conduction_errors, erf};
use floe_engine::scene::load::from_preset;

fn sim(preset: &str, overrides: &[&str]) -> Simulation {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Simulation::new_cpu(from_preset(preset, &overrides).unwrap()).unwrap()
}

fn measure(sim: &Simulation, name: &str) -> f64 {
    sim.measures().into_iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no measure {name}")).value
}

#[test]
fn erf_matches_tabulated_values() {
    for (x, want) in [(0.0, 0.0), (0.5, 0.520_499_877_8), (1.0, 0.842_700_792_9), (2.0, 0.995_322_265_0)] {
        assert!((erf(x) - want).abs() < 2e-7, "erf({x}) = {}", erf(x));
        assert!((erf(-x) + want).abs() < 2e-7);
    }
}

/// The slab at two resolutions: the error against the erf solution is at most 1 %
/// at the finer and smaller than at the coarser.
#[test]
fn conduction_between_half_spaces_follows_the_erf_solution() {
    let mut errors = Vec::new();
    for spacing in [0.002, 0.001] {
        let mut s = sim("conduction", &[&format!("particle_spacing={spacing}")]);
        while s.time() < 0.16 {
            s.step().unwrap();
        }
        let (l2, linf) = conduction_errors(&s);
        eprintln!("spacing {spacing}: {} steps, L2 {l2:.3e}, Linf {linf:.3e}", s.steps());
        errors.push(l2);
    }
    assert!(errors[1] <= 0.01, "L2 {} above 1 %", errors[1]);
    assert!(errors[1] < errors[0], "no convergence: {errors:?}");
}

/// Insulated walls and no sources: conduction only moves heat between particles,
/// and the pairwise form is antisymmetric, so the total stays put while a hot
/// corner spreads out.
#[test]
fn an_insulated_box_conserves_heat_over_1000_steps() {
    let mut s = sim(
        "convection",
        &[
            "particle_spacing=0.01",
            "heat.walls=[]",
            "heat.fluids[0].conductivity=5000",
            "heat.regions=[{\"min\":[0,0.05,0],\"max\":[0.2,0.06,0.04],\"temperature\":350}]",
        ],
    );
    let (q0, hot0) = (measure(&s, "heat.total_heat"), measure(&s, "heat.max_temperature"));
    for _ in 0..1000 {
        s.step().unwrap();
    }
    let (q1, hot1) = (measure(&s, "heat.total_heat"), measure(&s, "heat.max_temperature"));
    eprintln!("total heat {q0:.9e} -> {q1:.9e} J (relative {:.2e}); hottest {hot0} -> {hot1} K", (q1 - q0) / q0);
    assert!(hot1 < hot0 - 1.0, "heat did not spread: hottest {hot0} -> {hot1} K");
    assert!(((q1 - q0) / q0).abs() <= 1e-6, "total heat {q0} -> {q1} J");
}

/// The heat rate (W) of the insulated `convection` tank (no gravity, 1 cm spacing)
/// heated through its floor at `flux` W/m^2 over `steps` steps, and the flux times
/// the floor's area under the fluid (0.4 m x 0.04 m).
fn floor_flux_rate(flux: f64, heat_capacity: f64, steps: usize) -> (f64, f64) {
    let mut s = sim(
        "convection",
        &[
            "particle_spacing=0.01",
            "gravity=[0,0,0]",
            "solver.speed_of_sound=20",
            "heat.walls=[]",
            &format!("heat.fluids[0].heat_capacity={heat_capacity}"),
            &format!("heat.fluxes=[{{\"min\":[-1,-1,-1],\"max\":[1,0,1],\"flux\":{flux}}}]"),
        ],
    );
    let q0 = measure(&s, "heat.total_heat");
    for _ in 0..steps {
        s.step().unwrap();
    }
    let rate = (measure(&s, "heat.total_heat") - q0) / s.time();
    eprintln!("flux {flux} W/m^2, c {heat_capacity}: {rate:.4} W over {} s", s.time());
    (rate, flux * 0.4 * 0.04)
}

/// A heat flux through the floor of an insulated tank adds flux x floor area of heat
/// per second (the layer of fluid it enters through is the first, one spacing thick);
/// a negative one takes as much away. A small heat capacity makes each step's
/// increment many rounding units of a temperature near 310 K in f32.
#[test]
fn a_wall_flux_adds_flux_times_area() {
    for flux in [1e5, -1e5] {
        let (rate, want) = floor_flux_rate(flux, 100.0, 200);
        assert!((rate / want - 1.0).abs() < 1e-3, "{rate} W for {want} W");
    }
}

/// Water heated through its floor by a gentle 1 kW/m^2 gains its few 1e-6 K a step,
/// under half the f32 spacing of 310 K: the compensated integration keeps them (plain
/// `T += dt dT/dt` left the water at its temperature: 0 W).
#[test]
fn a_gentle_flux_warms_water_at_its_rate() {
    let (rate, want) = floor_flux_rate(1000.0, 4186.0, 2000);
    assert!((rate / want - 1.0).abs() < 0.01, "{rate} W for {want} W");
}

/// A snapshot of a heat scene written before the temperature's rounding carry was
/// kept (no `temperature_carry` section) restores, with no carry yet.
#[test]
fn a_snapshot_without_the_carry_restores() {
    let mut s = sim("convection", &["particle_spacing=0.02"]);
    for _ in 0..5 {
        s.step().unwrap();
    }
    let mut parts = floe_engine::snapshot::read(&s.snapshot()).unwrap();
    let before = parts.sections.len();
    parts.sections.retain(|x| x.name != "temperature_carry");
    assert_eq!(parts.sections.len(), before - 1);
    let restored = Simulation::restore(&floe_engine::snapshot::write(&parts)).unwrap();
    assert_eq!(restored.steps(), 5);
    assert_eq!(measure(&restored, "heat.total_heat"), measure(&s, "heat.total_heat"));
    // Any other missing state is still refused.
    parts.sections.retain(|x| x.name != "temperature");
    let err = Simulation::restore(&floe_engine::snapshot::write(&parts)).unwrap_err().to_string();
    assert!(err.contains("no section for attribute temperature (heat)"), "{err}");
}

/// A floor held at 330 K warms water at 310 K, never beyond the floor's temperature.
#[test]
fn a_hot_floor_warms_the_fluid() {
    let mut s = sim(
        "convection",
        &[
            "particle_spacing=0.01",
            "heat.fluids[0].conductivity=500",
            "heat.walls=[{\"min\":[-1,-1,-1],\"max\":[1,0,1],\"temperature\":330}]",
        ],
    );
    let mean0 = measure(&s, "heat.mean_temperature");
    for _ in 0..200 {
        s.step().unwrap();
    }
    let (mean1, hot) = (measure(&s, "heat.mean_temperature"), measure(&s, "heat.max_temperature"));
    assert!(mean1 > mean0 + 1e-3, "mean temperature {mean0} -> {mean1} K");
    assert!(hot <= 330.0 + 1e-3, "hottest particle {hot} K above the floor's 330 K");
}

/// Walls held at a temperature put it on their surface: steady conduction across the
/// heated cavity (no buoyancy, 10 particles between walls at 298 and 288 K, the
/// conductivity raised so it settles in 1 s) has the gradient 10 K / 5 cm. With the
/// walls' temperature at the wall particles, half a spacing outside, it was 9 % less.
#[test]
fn walls_hold_their_temperature_at_their_surface() {
    let mut s = sim(
        "heated_cavity",
        &["particle_spacing=0.005", "heat.fluids[0].expansion=0", "heat.fluids[0].conductivity=1408"],
    );
    while s.time() < 1.0 {
        s.step().unwrap();
    }
    let p = s.read(&["temperature"]);
    let t = p.channel("temperature").and_then(|c| c.as_scalars()).unwrap();
    // The least-squares slope of T(x) over every particle.
    let n = t.len() as f64;
    let (mut sx, mut st, mut sxx, mut sxt) = (0.0, 0.0, 0.0, 0.0);
    for (x, &ti) in p.positions.iter().zip(t) {
        let (x, ti) = (f64::from(x[0]), f64::from(ti));
        (sx, st, sxx, sxt) = (sx + x, st + ti, sxx + x * x, sxt + x * ti);
    }
    let slope = (n * sxt - sx * st) / (n * sxx - sx * sx);
    assert!((slope / -200.0 - 1.0).abs() < 0.02, "gradient {slope} K/m, want -200");
}

/// A source far too strong drives a particle above the scene's temperature range:
/// the scene halts, naming the quantity and the particle.
#[test]
fn temperature_outside_its_range_halts_the_scene() {
    let mut s = sim(
        "conduction",
        &["particle_spacing=0.002", "heat.sources=[{\"min\":[0,0,0],\"max\":[0.01,0.01,0.01],\"power\":1e12}]"],
    );
    let halted = (0..200).find_map(|_| s.step().err()).expect("the scene halts");
    assert!(halted.reason.contains("temperature") && halted.reason.contains("outside its range"), "{}", halted.reason);
    assert!(halted.particle.is_some());
}

#[test]
fn a_heat_section_must_match_the_fluids() {
    let overrides = vec!["heat.fluids=[]".to_string(), "heat.range=[300,200]".to_string()];
    let err = from_preset("conduction", &overrides).unwrap_err().to_string();
    assert!(err.contains("heat.fluids: must hold one entry per fluid (1), got 0"), "{err}");
    assert!(err.contains("heat.range[1]: must exceed range[0]"), "{err}");
    let flux = r#"{"min":[0,0,0],"max":[1,1,1],"flux":10}"#;
    let overrides = vec![
        r#"heat.fluxes=[{"min":[1,0,0],"max":[0,1,1],"flux":10}]"#.to_string(),
        format!("heat.sources=[{}]", [r#"{"min":[0,0,0],"max":[1,1,1],"power":1}"#; 8].join(",")),
    ];
    let err = from_preset("conduction", &overrides).unwrap_err().to_string();
    assert!(err.contains("heat.fluxes[0]"), "{err}");
    assert!(err.contains("heat.sources: at most 8 sources and fluxes together, got 9"), "{err}");
    let fine = vec![format!("heat.fluxes=[{flux}]")];
    assert!(from_preset("conduction", &fine).is_ok());
}

/// Conductivity and expansion are live settings; switching expansion off removes
/// the buoyancy pass, and on again restores it.
#[test]
fn conductivity_and_expansion_change_while_the_scene_runs() {
    let mut s = sim("convection", &["particle_spacing=0.01"]);
    let buoyant = |s: &Simulation| s.model().plan.passes().iter().any(|p| p.name == "heat.buoyancy");
    assert!(buoyant(&s));
    s.step().unwrap();
    s.set_parameters(&["heat.fluids[0].expansion=0".into(), "heat.fluids[0].conductivity=500".into()]).unwrap();
    assert!(!buoyant(&s));
    let k = s.model().consts::<floe_engine::modules::heat::HeatConsts>().conductivity[0];
    assert_eq!(k, 500.0);
    s.step().unwrap();
    s.set_parameters(&["heat.fluids[0].expansion=1e-3".into()]).unwrap();
    assert!(buoyant(&s));
    s.step().unwrap();
}
