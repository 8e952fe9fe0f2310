//! The transport velocity (`solver.transport_velocity`; Adami, Hu & Adams 2013):
//! the background pressure pushes nothing on an even lattice and pushes a displaced
//! particle back towards its place; the drift moves particles with `v + dt/2
//! a_transport` while their velocity never takes it; scenes with it restore bit for
//! bit, and scenes without it have no such attribute. The Taylor-Green case of
//! `floe validate` measures what it does to a flow.

use floe_engine::Simulation;
use floe_engine::attrs::Column;
use floe_engine::math::Vec3;
use floe_engine::modules::fluid::presets::TAYLOR_GREEN_WCSPH;
use floe_engine::plan::Stage;
use floe_engine::scene::load::{Format, from_preset, from_str};

const SPACING: f32 = 0.05;
/// Background pressure (Pa): `rho0 c^2` at c = 20 m/s.
const BACKGROUND: f32 = 4e5;

/// A fully periodic box of water at rest, 8 spacings a side, with the transport
/// velocity (or without, when `background` is `None`).
fn block(background: Option<f32>) -> Simulation {
    let side = 8.0 * SPACING;
    let transport = background.map_or(String::new(), |p| format!("transport_velocity = {{ background = {p} }}"));
    let text = format!(
        r#"
        name = "transport"
        particle_spacing = {SPACING}
        gravity = [0, 0, 0]
        periodic = ["x", "y", "z"]
        domain = {{ min = [0, 0, 0], max = [{side}, {side}, {side}] }}
        [[fluids]]
        blocks = [{{ min = [0, 0, 0], max = [{side}, {side}, {side}] }}]
        [solver]
        speed_of_sound = 20
        {transport}
        "#
    );
    Simulation::new_cpu(from_str(&text, Format::Toml, &[]).unwrap()).unwrap()
}

fn vectors(column: Column) -> Vec<Vec3> {
    let Column::Vec3(v) = column else { panic!("a vector attribute") };
    v
}

/// Evaluates the forces and returns `(id, x, a_transport)` of every particle.
fn evaluate(sim: &mut Simulation) -> Vec<(u32, Vec3, Vec3)> {
    let b = sim.backend_mut();
    for stage in [Stage::Sort, Stage::Density, Stage::PreForce, Stage::Force] {
        b.run(stage, 0.0);
    }
    let mut got = b.download(&["id", "x", "a_transport"]).into_iter();
    let Some(Column::U32(ids)) = got.next() else { panic!("ids are u32") };
    let (x, a) = (vectors(got.next().unwrap()), vectors(got.next().unwrap()));
    ids.into_iter().zip(x).zip(a).map(|((i, x), a)| (i, x, a)).collect()
}

#[test]
fn an_even_lattice_feels_no_push_and_a_displaced_particle_is_pushed_back() {
    let mut sim = block(Some(BACKGROUND));
    let even = evaluate(&mut sim).iter().map(|p| p.2.length()).fold(0.0, f32::max);

    // Particle 100 moved a fifth of a spacing along +x, towards its neighbour.
    let mut x = vectors(sim.backend().download(&["x"]).remove(0));
    let ids = match sim.backend().download(&["id"]).remove(0) {
        Column::U32(ids) => ids,
        _ => unreachable!(),
    };
    let slot = ids.iter().position(|&i| i == 100).unwrap();
    x[slot].x += 0.2 * SPACING;
    sim.backend_mut().upload("x", Column::Vec3(x));
    let after = evaluate(&mut sim);
    let (_, _, push) = *after.iter().find(|p| p.0 == 100).unwrap();
    // The push is an acceleration of order p_b / (rho0 h) (m/s^2).
    let scale = BACKGROUND / (1000.0 * SPACING);
    assert!(even < 1e-4 * scale, "an even lattice is pushed at {even} m/s^2");
    assert!(push.x < -0.05 * scale, "the displaced particle is pushed along x at {} m/s^2", push.x);
    assert!(push.y.abs().max(push.z.abs()) < 1e-3 * push.x.abs(), "push {push} leaves the x axis");
}

#[test]
fn the_drift_moves_with_the_push_and_the_velocity_does_not_take_it() {
    let mut sim = block(Some(BACKGROUND));
    let b = sim.backend_mut();
    let n = b.model().particle_count();
    let x0 = vectors(b.download(&["x"]).remove(0));
    let (v, a_t) = (Vec3::new(0.5, -0.25, 0.125), Vec3::new(40.0, 20.0, -10.0));
    b.upload("v", Column::Vec3(vec![v; n]));
    b.upload("a_transport", Column::Vec3(vec![a_t; n]));
    let dt = 1e-3;
    b.drift(dt);
    b.end_step();
    let (x1, v1) = (vectors(b.download(&["x"]).remove(0)), vectors(b.download(&["v"]).remove(0)));
    for k in 0..3 {
        let moved = f64::from(x1[0][k]) - f64::from(x0[0][k]);
        let want = f64::from(dt) * (f64::from(v[k]) + 0.5 * f64::from(dt) * f64::from(a_t[k]));
        assert!((moved - want).abs() < 1e-7, "axis {k}: moved {moved} m, want {want} m");
    }
    assert!(v1.iter().all(|&w| w == v), "the drift changed velocities");
}

#[test]
fn scenes_with_it_restore_bit_for_bit_and_scenes_without_it_have_no_push() {
    let wcsph = TAYLOR_GREEN_WCSPH.map(String::from);
    let mut sim = Simulation::new_cpu(from_preset("taylor_green", &wcsph).unwrap()).unwrap();
    assert!(sim.model().layout.spec("a_transport").is_some());
    for _ in 0..10 {
        sim.step().unwrap();
    }
    let saved = sim.snapshot();
    for _ in 0..10 {
        sim.step().unwrap();
    }
    let mut restored = Simulation::restore(&saved).unwrap();
    for _ in 0..10 {
        restored.step().unwrap();
    }
    assert_eq!(restored.snapshot(), sim.snapshot());
    assert!(block(None).model().layout.spec("a_transport").is_none());
    let plain = Simulation::new_cpu(from_preset("taylor_green", &[wcsph[0].clone()]).unwrap());
    assert!(plain.unwrap().model().layout.spec("a_transport").is_none());
}
