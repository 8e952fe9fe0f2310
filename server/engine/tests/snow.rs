//! The snow module on the CPU: the viscous force only dissipates, explicitly and
//! implicitly; channel flows at CI's coarsest resolution against their steady
//! profiles (the implicit solve far above the explicit limit on dt); the section's
//! validation and the live rheology.

use floe_engine::Simulation;
use floe_engine::attrs::Column;
use floe_engine::modules::snow::SnowConsts;
use floe_engine::modules::snow::cases::CHANNEL_T_END;
use floe_engine::modules::snow::channel;
use floe_engine::plan::Stage;
use floe_engine::scene::load::from_preset;

fn sim(preset: &str, overrides: &[&str]) -> Simulation {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Simulation::new_cpu(from_preset(preset, &overrides).unwrap()).unwrap()
}

/// The implicit solve (the default), and the explicit force.
const IMPLICIT: &str = "snow.solver={\"method\":\"implicit\"}";
const EXPLICIT: &str = "snow.solver={\"method\":\"explicit\"}";

fn measure(s: &Simulation, name: &str) -> f64 {
    s.measures().into_iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no measure {name}")).value
}

/// A velocity field with no structure, of magnitudes from 1 to 50 mm/s: every pair
/// of neighbours shears, some slowly, some fast.
fn scrambled(n: usize) -> Column {
    let mut state = 0x2545_f491_u32;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state as f32 / u32::MAX as f32) - 0.5
    };
    let v = (0..n).map(|i| floe_engine::math::Vec3::new(next(), next(), next()) * (1e-3 * (1 + i % 50) as f32));
    Column::Vec3(v.collect())
}

/// `sum_i m_i v_i . a_i` of the viscous force alone is negative for any velocity
/// field, with viscosities that differ from particle to particle (a shear-thinning
/// law on a scrambled flow) and with walls.
#[test]
fn the_viscous_force_only_dissipates() {
    let mut s = sim("cross_channel", &["particle_spacing=0.1", EXPLICIT]);
    let n = s.particle_count();
    let b = s.backend_mut();
    b.upload("v", scrambled(n));
    for stage in [Stage::Sort, Stage::Density, Stage::PreForce] {
        b.run(stage, 1e-3);
    }
    b.upload("a", Column::Vec3(vec![Default::default(); n]));
    b.run_pass("viscosity.force", 1e-3);
    b.end_step();
    let columns = b.download(&["v", "a", "mu"]);
    let (Column::Vec3(v), Column::Vec3(a), Column::F32(mu)) = (&columns[0], &columns[1], &columns[2]) else {
        panic!("velocities, accelerations and viscosities")
    };
    let spread = mu.iter().fold(0.0f32, |m, &x| m.max(x)) / mu.iter().fold(f32::MAX, |m, &x| m.min(x));
    assert!(spread > 2.0, "the viscosities differ between particles (max/min {spread})");
    let power: f64 = v.iter().zip(a).map(|(v, a)| f64::from(v.dot(*a))).sum();
    let scale: f64 = a.iter().map(|a| f64::from(a.length())).sum::<f64>() * 0.5;
    assert!(power < -1e-3 * scale, "viscous power {power} (scale {scale})");
}

/// The power-law channel at 10 layers across with the explicit force, stepping at
/// its viscous limit: within 3 % of the closed form.
#[test]
fn a_power_law_channel_reaches_its_closed_form() {
    let mut s = sim("power_law_channel", &["particle_spacing=0.1", EXPLICIT]);
    while s.time() < CHANNEL_T_END {
        s.step().unwrap();
    }
    let limit = measure(&s, "snow.explicit_dt_limit");
    assert!((s.stats().dt_mean - limit).abs() < 1e-3 * limit, "dt {} at the limit {limit}", s.stats().dt_mean);
    let law = s.model().consts::<SnowConsts>().laws[0];
    let p = s.read(&["velocity"]);
    let (k, n) = (f64::from(law.p[0]), f64::from(law.p[1]));
    let l2 = channel::l2_error(&p, |y| channel::power_law(y, 100.0, k, n, 1.0));
    assert!(l2 < 0.03, "velocity L2 {l2}");
    // A Newtonian fluid of the wall's viscosity flows slower in the middle: the
    // shear-thickening profile is blunter than the parabola.
    let newtonian = channel::l2_error(&p, |y| 0.05 * y * (1.0 - y));
    assert!(newtonian > 0.1, "L2 against the parabola {newtonian}");
}

/// With the implicit solve the Cross channel reaches its steady profile as the
/// explicit force does, at steps well above the explicit viscous limit, and each
/// step reports its solve.
#[test]
fn implicit_viscosity_reaches_the_channel_profile_at_larger_steps() {
    let mut s = sim("cross_channel", &["particle_spacing=0.1", IMPLICIT]);
    while s.time() < CHANNEL_T_END {
        let report = s.step().unwrap();
        let solve = report.solves[0];
        assert_eq!(solve.name, "viscosity");
        assert!(solve.iterations >= 1 && solve.residual <= 1e-3, "{solve:?}");
    }
    let limit = measure(&s, "snow.explicit_dt_limit");
    assert!(s.stats().dt_mean > 5.0 * limit, "mean dt {} against the explicit limit {limit}", s.stats().dt_mean);
    let law = s.model().consts::<SnowConsts>().laws[0];
    let profile = channel::steady_profile(&law, 1000.0 * f64::from(s.scene().gravity[0]), 1.0, 2000);
    let l2 = channel::l2_error(&s.read(&["velocity"]), |y| profile.at(y));
    assert!(l2 < 0.03, "velocity L2 {l2}");
}

/// Backward Euler only dissipates: one solve on a scrambled flow (viscosities that
/// differ between particles, no-slip walls) at a dt 1000 times the explicit limit
/// lowers the kinetic energy; a flow at rest stays at rest, its residual 0.
#[test]
fn the_implicit_solve_only_dissipates() {
    let mut s = sim("cross_channel", &["particle_spacing=0.1", IMPLICIT]);
    let n = s.particle_count();
    let dt = 1000.0 * measure(&s, "snow.explicit_dt_limit") as f32;
    let solve = s.model().velocity_solves[0];
    let energy = |s: &Simulation| match &s.backend().download(&["v"])[0] {
        Column::Vec3(v) => v.iter().map(|v| f64::from(v.length_squared())).sum::<f64>(),
        _ => panic!("velocities"),
    };
    for (velocities, expect_rest) in [(scrambled(n), false), (Column::Vec3(vec![Default::default(); n]), true)] {
        let b = s.backend_mut();
        b.upload("v", velocities);
        for stage in [Stage::Sort, Stage::Density, Stage::PreForce] {
            b.run(stage, dt);
        }
        let before = energy(&s);
        let report = solve.run(s.backend_mut(), dt).unwrap();
        let after = energy(&s);
        if expect_rest {
            assert_eq!((report.iterations, report.residual, after), (1, 0.0, 0.0), "{report:?}");
        } else {
            assert!(report.residual <= 1e-3 && report.iterations > 1, "{report:?}");
            assert!(after < 0.5 * before, "kinetic energy {before} -> {after}");
        }
    }
}

#[test]
fn a_snow_section_is_checked_field_by_field() {
    let overrides = vec![
        "snow.fluids=[{\"model\":\"power_law\",\"k\":1,\"n\":20},{\"model\":\"none\"}]".to_string(),
        "snow.max_viscosity=-1".to_string(),
    ];
    let err = from_preset("power_law_channel", &overrides).unwrap_err().to_string();
    assert!(err.contains("snow.fluids: must hold one entry per fluid (1), got 2"), "{err}");
    assert!(err.contains("snow.fluids[0].n"), "{err}");
    assert!(err.contains("snow.max_viscosity"), "{err}");
    let solver = vec!["snow.solver={\"method\":\"implicit\",\"tolerance\":2,\"max_iterations\":0}".to_string()];
    let err = from_preset("cross_channel", &solver).unwrap_err().to_string();
    assert!(err.contains("snow.solver.tolerance: must be between"), "{err}");
    assert!(err.contains("snow.solver.max_iterations: must be 1 to 10000, got 0"), "{err}");
    let negative = vec!["snow.fluids[0].yield_stress=-5".to_string()];
    let err = from_preset("bingham_channel", &negative).unwrap_err().to_string();
    assert!(err.contains("snow.fluids[0].yield_stress"), "{err}");
}

/// The rheology is a live setting: the new law's viscosity reaches the particles
/// at the next step.
#[test]
fn the_rheology_changes_while_the_scene_runs() {
    let mut s = sim("cross_channel", &["particle_spacing=0.1"]);
    s.step().unwrap();
    s.set_parameters(&["snow.fluids[0]={\"model\":\"newtonian\",\"mu\":42}".into()]).unwrap();
    s.step().unwrap();
    let p = s.read(&["viscosity"]);
    let mu = p.channel("viscosity").and_then(|c| c.as_scalars()).unwrap();
    assert!(mu.iter().all(|&m| m == 42.0), "{:?}", &mu[..4]);
}
