//! δ-SPH (`solver.delta_sph`): the density integrated by the continuity equation
//! with a diffusion term. Without diffusion its rate is the time derivative of the
//! summed density, walls included; the diffusion smooths a bump and keeps the
//! volume-weighted total; each particle starts under the weight of the fluid above
//! it (none where gravity runs along a periodic axis), so a column starts in
//! hydrostatic balance, where the diffusion does nothing; a resting column's pressure is smooth
//! where the summed one is noisy; scenes with it restore bit for bit under both
//! integrators, and scenes without it sum their density and allocate nothing of it.

use floe_engine::Simulation;
use floe_engine::attrs::{Column, Role};
use floe_engine::math::Vec3;
use floe_engine::plan::Stage;
use floe_engine::scene::load::{Format, from_preset, from_str};
use floe_engine::validation::hydrostatic;

const WCSPH: &str = "solver.method=\"wcsph\"";

const SPACING: f32 = 0.05;

/// A box of water 12 spacings a side, periodic along every axis, no gravity,
/// with δ-SPH (diffusion `delta`) and the scene's `overrides`.
fn periodic_block(delta: f32, overrides: &[String]) -> Simulation {
    let side = 12.0 * SPACING;
    let text = format!(
        r#"
        name = "delta"
        particle_spacing = {SPACING}
        gravity = [0, 0, 0]
        periodic = ["x", "y", "z"]
        domain = {{ min = [0, 0, 0], max = [{side}, {side}, {side}] }}
        [[fluids]]
        blocks = [{{ min = [0, 0, 0], max = [{side}, {side}, {side}] }}]
        [solver]
        speed_of_sound = 20
        delta_sph = {{ delta = {delta} }}
        "#
    );
    Simulation::new_cpu(from_str(&text, Format::Toml, overrides).unwrap()).unwrap()
}

fn floats(column: Column) -> Vec<f32> {
    let Column::F32(v) = column else { panic!("a scalar attribute") };
    v
}

fn vectors(column: Column) -> Vec<Vec3> {
    let Column::Vec3(v) = column else { panic!("a vector attribute") };
    v
}

/// Runs the stages up to the drift's passes (the density's rate) at `dt`.
fn rate(sim: &mut Simulation) -> Vec<f32> {
    let b = sim.backend_mut();
    for stage in [Stage::Sort, Stage::Density, Stage::PreForce, Stage::Force] {
        b.run(stage, 0.0);
    }
    b.run_pass("wcsph.continuity", 0.0);
    floats(b.download(&["drho"]).remove(0))
}

/// `id -> value` of a column downloaded with the ids.
fn by_id(sim: &Simulation, name: &str) -> Vec<f32> {
    let mut got = sim.backend().download(&["id", name]).into_iter();
    let Some(Column::U32(ids)) = got.next() else { panic!("ids are u32") };
    let values = floats(got.next().unwrap());
    let mut out = vec![0.0; ids.len()];
    for (id, v) in ids.into_iter().zip(values) {
        out[id as usize] = v;
    }
    out
}

#[test]
fn its_rate_is_the_time_derivative_of_the_summed_density_walls_included() {
    // A swirling, compressing velocity field over the dam break's column in its
    // tank: the continuity equation's rate (no diffusion) against the central
    // difference of the summed density along it, particle by particle.
    let o = |delta: bool| {
        let mut o = vec![
            "particle_spacing=0.1".to_string(),
            WCSPH.into(),
            "gravity=[0,0,0]".into(),
            "solver.speed_of_sound=20".into(),
        ];
        if delta {
            o.push("solver.delta_sph={\"delta\":0}".into());
        }
        Simulation::new_cpu(from_preset("dam_break", &o).unwrap()).unwrap()
    };
    let mut integrated = o(true);
    let x = vectors(integrated.backend().download(&["x"]).remove(0));
    let field = |x: Vec3| Vec3::new((3.0 * x.y).sin() - 0.5 * x.x, (2.0 * x.x).cos() - 0.8 * x.y, 0.3 - 0.4 * x.z);
    let v: Vec<Vec3> = x.iter().map(|&x| field(x)).collect();
    integrated.backend_mut().upload("v", Column::Vec3(v.clone()));
    rate(&mut integrated);
    let drho = by_id(&integrated, "drho");
    let eps = 1e-3;
    // A new scene each time: uploads are in the unsorted (id) order.
    let at = |sign: f32| {
        let moved: Vec<Vec3> = x.iter().zip(&v).map(|(&x, &v)| x + v * (sign * eps)).collect();
        let mut summed = o(false);
        summed.backend_mut().upload("x", Column::Vec3(moved));
        summed.backend_mut().run(Stage::Sort, 0.0);
        summed.backend_mut().run(Stage::Density, 0.0);
        by_id(&summed, "rho")
    };
    let (ahead, behind) = (at(1.0), at(-1.0));
    let scale = drho.iter().fold(0.0f32, |m, d| m.max(d.abs()));
    assert!(scale > 100.0, "the field barely compresses: {scale} kg/(m^3 s)");
    for (i, &d) in drho.iter().enumerate() {
        let fd = (ahead[i] - behind[i]) / (2.0 * eps);
        assert!((d - fd).abs() < 0.01 * scale, "particle {i}: drho/dt = {d}, the summed density's {fd}");
    }
}

#[test]
fn the_diffusion_smooths_a_density_bump_and_conserves_its_total() {
    let mut sim = periodic_block(0.1, &[]);
    let mut rho = floats(sim.backend().download(&["rho"]).remove(0));
    rho[300] += 10.0;
    sim.backend_mut().upload("rho", Column::F32(rho.clone()));
    let drho = rate(&mut sim);
    let rho_sorted = floats(sim.backend().download(&["rho"]).remove(0));
    let bump = rho_sorted.iter().position(|&r| r > 1005.0).expect("the bump survives the sort");
    assert!(drho[bump] < 0.0, "the bump's own density rises at {} kg/(m^3 s)", drho[bump]);
    assert!(drho.iter().enumerate().filter(|(i, _)| *i != bump).any(|(_, &d)| d > 0.0));
    // The pairwise flux weighted by each particle's volume m / rho is antisymmetric:
    // sum_i drho_i / rho_i is kept.
    let total: f64 = drho.iter().zip(&rho_sorted).map(|(&d, &r)| f64::from(d / r)).sum();
    let scale: f64 = drho.iter().zip(&rho_sorted).map(|(&d, &r)| f64::from(d.abs() / r)).sum();
    assert!(total.abs() < 1e-4 * scale, "the diffusion adds {total} of {scale}");
}

#[test]
fn a_fluid_diffuses_and_dissipates_at_its_own_speed_of_sound() {
    // The block's water at the scene's c = 20 m/s, then as a linear law of stiffness
    // 4 c^2 (sounding at 2 c): at rest density neither has a pressure, so a density
    // bump's rate is the diffusion's alone and a converging flow's acceleration the
    // artificial viscosity's, and both must double.
    let run = |eos: &str| {
        let o = ["fluids[0].viscosity={\"model\":\"artificial\",\"alpha\":0.1}".to_string(), eos.to_string()];
        let mut sim = periodic_block(0.1, &o);
        let mut rho = floats(sim.backend().download(&["rho"]).remove(0));
        rho[300] += 10.0;
        sim.backend_mut().upload("rho", Column::F32(rho));
        let drho = rate(&mut sim);
        let bump = drho.iter().fold(0.0f32, |m, d| m.min(*d));
        let mut sim = periodic_block(0.1, &o);
        let x = vectors(sim.backend().download(&["x"]).remove(0));
        let centre = Vec3::splat(6.0 * SPACING);
        sim.backend_mut().upload("v", Column::Vec3(x.iter().map(|&x| centre - x).collect()));
        rate(&mut sim);
        let a = vectors(sim.backend().download(&["a"]).remove(0));
        (bump, a.iter().map(|a| a.length()).fold(0.0f32, f32::max))
    };
    let (bump, a) = run("fluids[0].eos={\"kind\":\"tait\"}");
    let (stiff_bump, stiff_a) = run("fluids[0].eos={\"kind\":\"linear\",\"stiffness\":1600}");
    assert!(bump < -1.0 && a > 0.1, "the bump falls at {bump} kg/(m^3 s), the flow slows at {a} m/s^2");
    assert!((stiff_bump / bump - 2.0).abs() < 1e-4, "diffusion {stiff_bump} against {bump} at c");
    assert!((stiff_a / a - 2.0).abs() < 1e-4, "artificial viscosity {stiff_a} against {a} at c");
}

#[test]
fn a_resting_column_starts_in_balance_and_its_pressure_is_smooth() {
    let lin = "fluids[0].eos={\"kind\":\"linear\"}".to_string();
    let column = |delta: bool| {
        // The preset's column as it was before it moved to DFSPH.
        let mut o = vec![
            "particle_spacing=0.05".to_string(),
            lin.clone(),
            "solver.method=\"wcsph\"".into(),
            "solver.kernel=\"cubic_spline\"".into(),
        ];
        if delta {
            o.push("solver.delta_sph={\"delta\":0.1}".into());
        }
        Simulation::new_cpu(from_preset("hydrostatic", &o).unwrap()).unwrap()
    };
    // With the linear law the starting density is exactly the hydrostatic one the
    // diffusion leaves alone: at rest, the first rate is rounding only.
    let mut sim = column(true);
    let drho = rate(&mut sim);
    let worst = drho.iter().fold(0.0f32, |m, d| m.max(d.abs()));
    assert!(worst < 1e-2, "a column in balance changes its density at {worst} kg/(m^3 s)");

    let measure = |mut sim: Simulation| {
        while sim.time() < 1.0 {
            sim.step().unwrap();
        }
        let p = sim.read(&["density", "pressure"]);
        hydrostatic::measure(&p, 1000.0, 9.81, 0.9, 0.05)
    };
    let (smooth, summed) = (measure(column(true)), measure(column(false)));
    assert!(smooth.pressure_linf < 0.06, "δ-SPH's worst pressure is {} off", smooth.pressure_linf);
    assert!(
        smooth.pressure_linf < 0.5 * summed.pressure_linf,
        "δ-SPH {} against summation {}",
        smooth.pressure_linf,
        summed.pressure_linf
    );
}

#[test]
fn each_particle_starts_under_the_weight_of_the_fluid_above_it() {
    use floe_engine::overburden::overburden;
    // Two columns 0.1 m apart, four particles each: 100 kg/m^3 over 1000 kg/m^3.
    let d = 0.1;
    let x: Vec<Vec3> = (0..8).map(|k| Vec3::new(0.05 + d * (k / 4) as f32, 0.05 + d * (k % 4) as f32, 0.05)).collect();
    let rho0: Vec<f32> = x.iter().map(|x| if x.y > 0.2 { 100.0 } else { 1000.0 }).collect();
    let p = overburden(&x, &rho0, Vec3::new(0.0, -10.0, 0.0), d);
    // Per column, bottom to top: half its own layer plus every layer above.
    let want = [10.0 * (500.0 + 1000.0 + 200.0), 10.0 * (500.0 + 200.0), 10.0 * (50.0 + 100.0), 10.0 * 50.0];
    for (k, &p) in p.iter().enumerate() {
        assert!((p - want[k % 4] * d).abs() < 1e-3, "particle {k}: {p} Pa, want {}", want[k % 4] * d);
    }
    assert!(overburden(&x, &rho0, Vec3::ZERO, d).iter().all(|&p| p == 0.0));
    // Gravity along a periodic axis (Poiseuille's driving force): no weight above, rest density.
    let channel = from_preset("poiseuille", &["solver.delta_sph={\"delta\":0.1}".into()]).unwrap();
    let rho = floats(Simulation::new_cpu(channel).unwrap().backend().download(&["rho"]).remove(0));
    assert!(rho.iter().all(|&r| r == 1000.0));
}

#[test]
fn scenes_with_it_restore_bit_for_bit_with_either_integrator() {
    for integrator in ["symplectic_euler", "leapfrog"] {
        let o = [
            "particle_spacing=0.1".to_string(),
            WCSPH.into(),
            format!("solver.integrator=\"{integrator}\""),
            "solver.delta_sph={\"delta\":0.1}".into(),
        ];
        let mut sim_delta = Simulation::new_cpu(from_preset("dam_break", &o).unwrap()).unwrap();
        assert_eq!(sim_delta.model().layout.spec("rho").unwrap().role, Role::State);
        for _ in 0..20 {
            sim_delta.step().unwrap();
        }
        let saved = sim_delta.snapshot();
        for _ in 0..20 {
            sim_delta.step().unwrap();
        }
        let mut restored = Simulation::restore(&saved).unwrap();
        for _ in 0..20 {
            restored.step().unwrap();
        }
        assert_eq!(restored.snapshot(), sim_delta.snapshot(), "{integrator}");
    }
}

#[test]
fn scenes_without_it_sum_their_density_and_allocate_nothing_of_it() {
    let plain =
        Simulation::new_cpu(from_preset("dam_break", &["particle_spacing=0.1".into(), WCSPH.into()]).unwrap()).unwrap();
    let names: Vec<&str> = plain.model().plan.passes().iter().map(|p| p.name).collect();
    assert!(names.contains(&"core.density"));
    assert!(!names.iter().any(|n| *n == "core.neighbours" || n.starts_with("wcsph.continuity")));
    assert!(plain.model().layout.spec("drho").is_none());
    assert_eq!(plain.model().layout.spec("rho").unwrap().role, Role::Derived);

    let delta = periodic_block(0.1, &[]);
    let names: Vec<&str> = delta.model().plan.passes().iter().map(|p| p.name).collect();
    assert!(!names.contains(&"core.density"));
    for pass in ["core.neighbours", "wcsph.continuity", "wcsph.integrate_density"] {
        assert!(names.contains(&pass), "{pass} missing from {names:?}");
    }
}
