//! Temperature-dependent viscosity on the CPU: each particle takes its law's
//! viscosity at its temperature, the heated channel's steady profile, the explicit
//! viscous limit, a law scaling a snow rheology, and the laws' validation.

use floe_engine::Simulation;
use floe_engine::modules::heat::HeatConsts;
use floe_engine::modules::heat::cases::channel_profile;
use floe_engine::modules::heat::presets::CHANNEL_T;
use floe_engine::modules::snow::SnowConsts;
use floe_engine::scene::load::from_preset;
use floe_engine::validation::poiseuille::profile_l2_error;

fn sim(preset: &str, overrides: &[&str]) -> Simulation {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Simulation::new_cpu(from_preset(preset, &overrides).unwrap()).unwrap()
}

fn error(preset: &str, overrides: &[&str]) -> String {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match from_preset(preset, &overrides) {
        Err(e) => e.to_string(),
        Ok(scene) => Simulation::new_cpu(scene).map(|_| ()).expect_err("the scene is refused").to_string(),
    }
}

/// The channel without conduction, its lower half at 285 K and its upper at 315 K:
/// every particle's viscosity is its law's at its temperature (the pass runs before
/// the forces, on the temperatures of the step's start, which stay put here).
#[test]
fn each_particle_takes_its_laws_viscosity_at_its_temperature() {
    let mut s = sim(
        "heated_channel",
        &[
            "particle_spacing=0.1",
            "heat.fluids[0].conductivity=0",
            "heat.fluids[0].temperature=315",
            r#"heat.regions=[{"min":[0,0,0],"max":[1,0.5,1],"temperature":285}]"#,
        ],
    );
    for _ in 0..3 {
        s.step().unwrap();
    }
    let law = s.model().consts::<HeatConsts>().viscosity[0];
    let p = s.read(&["viscosity", "temperature"]);
    let mu = p.channel("viscosity").and_then(|c| c.as_scalars()).unwrap();
    let t = p.channel("temperature").and_then(|c| c.as_scalars()).unwrap();
    let (lo, hi) = t.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    assert!(lo < 295.0 && hi > 305.0, "temperatures {lo} to {hi}");
    for (&mu, &t) in mu.iter().zip(t) {
        let want = 1000.0 * (-(4f32.ln() / 40.0) * (t - 300.0)).exp();
        assert!((mu - want).abs() <= 1e-4 * want, "mu {mu} at {t} K, law {want}");
        assert_eq!(mu, law.viscosity(t));
    }
}

/// The steady channel between plates at 280 and 320 K: the viscosity falls fourfold
/// towards the hot plate, so the flow is faster there than near the cold one, and
/// the velocities follow the quadrature profile of the law along the linear
/// temperature profile.
#[test]
fn the_heated_channel_runs_faster_near_its_hot_plate() {
    let mut s = sim("heated_channel", &["particle_spacing=0.1"]);
    while s.time() < 1.0 {
        s.step().unwrap();
    }
    let law = s.model().consts::<HeatConsts>().viscosity[0];
    let (cold, hot) = (f64::from(CHANNEL_T.0), f64::from(CHANNEL_T.1));
    let cells = 2000;
    let u = channel_profile(|y| f64::from(law.viscosity((cold + (hot - cold) * y) as f32)), 100.0, 1.0, cells);
    let p = s.read(&["velocity"]);
    let l2 = profile_l2_error(&p, |y| u[((y.clamp(0.0, 1.0) * cells as f64).round() as usize).min(cells)]);
    assert!(l2 < 0.02, "velocity L2 {l2}");
    let v = p.channel("velocity").and_then(|c| c.as_vectors()).unwrap();
    let at = |y: f32| {
        let near: Vec<f32> =
            p.positions.iter().zip(v).filter(|(x, _)| (x[1] - y).abs() < 0.01).map(|(_, v)| v[0]).collect();
        near.iter().sum::<f32>() / near.len() as f32
    };
    // The same distance from each plate: the hot side runs at about twice the speed.
    let (u_cold, u_hot) = (at(0.15), at(0.85));
    assert!(u_hot > 1.5 * u_cold, "{u_cold} m/s near the cold plate, {u_hot} near the hot one");
}

/// With the explicit force the viscous limit at the law's largest viscosity within
/// `heat.range` (270 K: 2828 Pa s) sets dt; the implicit solve lifts it.
#[test]
fn the_explicit_force_steps_under_the_viscous_limit() {
    let explicit = r#"heat.viscous_solver={"method":"explicit"}"#;
    let mut e = sim("heated_channel", &["particle_spacing=0.1", explicit]);
    let mut i = sim("heated_channel", &["particle_spacing=0.1"]);
    let h = 0.5 * e.model().kernel.support();
    let mu_max = 1000.0 * (4f32.ln() / 40.0 * 30.0).exp();
    let limit = 0.125 * h * h * 1000.0 / mu_max;
    let dt = e.step().unwrap().dt;
    assert!(dt <= limit * 1.0001 && dt > 0.5 * limit, "dt {dt}, limit {limit}");
    assert!(i.step().unwrap().dt > 1.5 * dt, "the implicit solve is not bound by the viscous limit");
}

/// A scene without a temperature law allocates no per-particle viscosity and runs
/// none of its passes.
#[test]
fn a_scene_without_a_law_has_no_per_particle_viscosity() {
    let s = sim("convection", &["particle_spacing=0.01"]);
    assert!(s.model().layout.spec("mu").is_none());
    let passes: Vec<&str> = s.model().plan.passes().iter().map(|p| p.name).collect();
    assert!(!passes.iter().any(|p| *p == "heat.viscosity" || p.starts_with("viscosity.")));
    assert!(!s.channels().iter().any(|c| c.name == "viscosity"));
    let with = sim("heated_channel", &["particle_spacing=0.1"]);
    assert!(with.channels().iter().any(|c| c.name == "viscosity" && c.unit == "Pa s"));
}

/// With the snow module as well, a fluid's temperature law scales its rheology: each
/// particle's viscosity is `mu(T) / mu(T0)` times the rheology's at its shear rate
/// (the channel's lower half at 285 K, its upper at 315 K, a shear-thickening power
/// law, T0 = 300 K, the law's fourfold fall across 40 K).
#[test]
fn a_temperature_law_scales_a_snow_rheology() {
    let mut s = sim(
        "heated_channel",
        &[
            "particle_spacing=0.1",
            r#"modules=["fluid","heat","snow"]"#,
            r#"snow={"fluids":[{"model":"power_law","k":2000,"n":1.5}],"max_viscosity":3000}"#,
            "heat.reference_temperature=300",
            "heat.fluids[0].conductivity=0",
            "heat.fluids[0].temperature=315",
            r#"heat.regions=[{"min":[0,0,0],"max":[1,0.5,1],"temperature":285}]"#,
        ],
    );
    while s.time() < 0.2 {
        s.step().unwrap();
    }
    let law = s.model().consts::<HeatConsts>().viscosity[0];
    let rheology = s.model().consts::<SnowConsts>().laws[0];
    assert!((law.shift(285.0) - 4f32.powf(15.0 / 40.0)).abs() < 1e-5, "{}", law.shift(285.0));
    assert!((law.shift(315.0) - 4f32.powf(-15.0 / 40.0)).abs() < 1e-5, "{}", law.shift(315.0));
    let p = s.read(&["viscosity", "temperature", "shear_rate"]);
    let column = |name: &str| p.channel(name).and_then(|c| c.as_scalars()).unwrap();
    let (mu, t, g) = (column("viscosity"), column("temperature"), column("shear_rate"));
    let sheared = g.iter().filter(|&&g| g > 1e-4).count();
    assert!(sheared > g.len() / 2, "{sheared} of {} particles sheared: {:?}", g.len(), &g[..8]);
    for ((&mu, &t), &g) in mu.iter().zip(t).zip(g) {
        let want = (law.shift(t) * rheology.viscosity(g)).min(rheology.max);
        assert!((mu - want).abs() <= 1e-5 * want, "mu {mu} at {t} K and {g} 1/s, want {want}");
    }
}

/// A law scales a rheology: a snow fluid without one has nothing to scale.
#[test]
fn a_temperature_law_needs_a_rheology_with_snow() {
    let err = error(
        "heated_channel",
        &["particle_spacing=0.1", r#"modules=["fluid","heat","snow"]"#, r#"snow={"fluids":[{"model":"none"}]}"#],
    );
    assert!(err.contains("snow.fluids[0].model: must not be \"none\""), "{err}");
    assert!(err.contains("heat.fluids[0].viscosity scales this fluid's viscosity"), "{err}");
}

#[test]
fn the_laws_are_checked() {
    let err = error("heated_channel", &[r#"fluids[0].viscosity={"model":"laplacian","nu":1}"#]);
    assert!(
        err.contains(
            "fluids[0].viscosity: must be {\"model\": \"none\"}: heat.fluids[0].viscosity sets this fluid's viscosity"
        ),
        "{err}"
    );
    let err = error(
        "heated_channel",
        &[r#"heat.fluids[0].viscosity={"law":"table","points":[[300,1],[290,2],[310,1e3],[320,-1]]}"#],
    );
    assert!(err.contains("heat.fluids[0].viscosity.points[1][0]: must exceed the previous point's 300"), "{err}");
    assert!(err.contains("heat.fluids[0].viscosity.points[3][1]"), "{err}");
    let err = error("heated_channel", &[r#"heat.fluids[0].viscosity={"law":"table","points":[[300,1]]}"#]);
    assert!(err.contains("must hold 2 to 8 points, got 1"), "{err}");
    let err = error(
        "heated_channel",
        &[
            r#"heat.fluids[0].viscosity={"law":"arrhenius","mu_ref":-1,"t_ref":293,"activation_temperature":1900}"#,
            r#"heat.viscous_solver={"method":"implicit","tolerance":0,"max_iterations":1}"#,
        ],
    );
    assert!(err.contains("heat.fluids[0].viscosity.mu_ref"), "{err}");
    assert!(err.contains("heat.viscous_solver.tolerance"), "{err}");
    let err = error("heated_channel", &["heat.max_viscosity=-1"]);
    assert!(err.contains("heat.max_viscosity"), "{err}");
}
