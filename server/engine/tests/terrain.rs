//! Fluid on terrain: Coulomb friction holds a block on a slope gentler than
//! `atan(mu)` and lets it slide down a steeper one.

use floe_engine::Simulation;
use floe_engine::math::Vec3;
use floe_engine::scene::load::{Format, from_str};
use floe_engine::terrain::source::rasterise_all;

const FRICTION: f32 = 0.4; // atan(0.4) = 21.8 degrees

/// A block of about 300 particles resting on a slope of `angle` degrees between two
/// side plates; after `seconds`, the mean speed along the surface of the particles
/// in contact with it (m/s).
fn contact_speed(angle: f32, seconds: f64) -> (f32, usize) {
    let (d, top) = (0.015f32, 0.4f32);
    let tan = angle.to_radians().tan();
    // Over x in [0.2, 0.32] the ground falls from h(0.2) to h(0.32); the block fills
    // down to the lowest point and the terrain drops what it buries.
    let (x0, x1) = (0.2f32, 0.32f32);
    let (low, high) = (top - tan * x1, top - tan * x0);
    let text = format!(
        r#"
        particle_spacing = {d}
        [[fluids]]
        rest_density = 1000
        blocks = [{{ min = [{x0}, {low}, 0], max = [{x1}, {}, 0.12] }}]
        [[boundaries]]
        kind = "terrain"
        min = [0, 0]
        max = [1, 0.12]
        friction = {FRICTION}
        layers = 2
        heights = {{ source = "slope", top = {top}, angle = {angle}, foot = 0.02, ripple = 0 }}
        [[boundaries]]
        kind = "box"
        min = [0, {}, 0]
        max = [1, {}, 0.12]
        open = ["-x", "+x", "-y", "+y"]
        [solver.time_step]
        mode = "adaptive"
        max = 5e-4
        "#,
        high + 0.1,
        -0.1,
        top + 0.3,
    );
    let scene = from_str(&text, Format::Toml, &[]).unwrap();
    let grid = rasterise_all(&scene).unwrap().remove(0).unwrap();
    let mut sim = Simulation::new_cpu(scene).unwrap();
    assert!((200..600).contains(&sim.particle_count()), "{} particles", sim.particle_count());
    sim.run_until(seconds, |_, _| {}).unwrap();
    let p = sim.read(&["velocity"]);
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).unwrap();
    let (mut sum, mut count) = (0.0, 0);
    for (x, v) in p.positions.iter().zip(v) {
        let (x, v) = (Vec3::from(*x), Vec3::from(*v));
        let (h, n) = grid.eval(x.x, x.z);
        if grid.covers(x.x, x.z) && (x.y - h) * n.y < d {
            sum += (v - n * v.dot(n)).length();
            count += 1;
        }
    }
    assert!(count > 20, "only {count} particles touch the ground");
    (sum / count as f32, count)
}

#[test]
fn fluid_rests_on_a_slope_gentler_than_the_friction_angle() {
    // The block spreads into a layer whose particles friction stops one by one.
    let (speed, n) = contact_speed(10.0, 1.0);
    eprintln!("10 degrees: {n} particles in contact, mean tangential speed {speed} m/s");
    assert!(speed < 0.02, "the contact layer still moves at {speed} m/s");
}

#[test]
fn fluid_slides_down_a_slope_steeper_than_the_friction_angle() {
    // Sliding block: g (sin a - mu cos a) = 2.4 m/s^2 at 35 degrees, 0.96 m/s after 0.4 s.
    let (speed, n) = contact_speed(35.0, 0.4);
    eprintln!("35 degrees: {n} particles in contact, mean tangential speed {speed} m/s");
    assert!(speed > 0.4, "the contact layer moves at only {speed} m/s");
}
