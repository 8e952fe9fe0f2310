//! Periodic boundaries: a block of fluid filling a fully periodic box is an infinite
//! medium (every particle sees a full lattice of neighbours, across the faces too),
//! uniform flow carries it through the faces without disturbing it, and scenes that
//! cannot be periodic are refused naming the field.

use floe_engine::Simulation;
use floe_engine::periodic::Periodicity;
use floe_engine::scene::load::{Format, from_str};

const SPACING: f32 = 0.05;
/// Eight spacings: a period of two kernel supports, the shortest allowed.
const SIDE: f32 = 8.0 * SPACING;

/// A box of side [`SIDE`] filled with water moving at `velocity`, no gravity, no
/// walls, periodic along `axes`.
fn block(axes: &str, velocity: [f32; 3]) -> Simulation {
    let text = format!(
        r#"
        name = "periodic"
        particle_spacing = {SPACING}
        gravity = [0, 0, 0]
        periodic = [{axes}]
        domain = {{ min = [0, 0, 0], max = [{SIDE}, {SIDE}, {SIDE}] }}
        [[fluids]]
        blocks = [{{ min = [0, 0, 0], max = [{SIDE}, {SIDE}, {SIDE}], velocity = {velocity:?} }}]
        [solver]
        speed_of_sound = 20
        "#
    );
    Simulation::new_cpu(from_str(&text, Format::Toml, &[]).unwrap()).unwrap()
}

fn densities(sim: &Simulation) -> Vec<f32> {
    sim.read(&["density"]).channel("density").and_then(|v| v.as_scalars()).unwrap().to_vec()
}

#[test]
fn a_fully_periodic_block_is_uniform_and_stays_at_rest() {
    let mut sim = block(r#""x", "y", "z""#, [0.0; 3]);
    sim.step().unwrap();
    let rho = densities(&sim);
    assert_eq!(rho.len(), 512);
    let (lo, hi) = rho.iter().fold((f32::MAX, f32::MIN), |(l, h), &r| (l.min(r), h.max(r)));
    // The particle mass is chosen so a full lattice sums to the rest density.
    assert!((lo - 1000.0).abs() < 0.01 && (hi - 1000.0).abs() < 0.01, "density between {lo} and {hi}");
    for _ in 0..50 {
        sim.step().unwrap();
    }
    let v = sim.read(&["velocity"]);
    let fastest = v
        .channel("velocity")
        .and_then(|v| v.as_vectors())
        .unwrap()
        .iter()
        .map(|v| v[0].abs().max(v[1].abs()).max(v[2].abs()))
        .fold(0.0, f32::max);
    assert!(fastest < 1e-4, "a uniform block at rest moved: {fastest} m/s");

    // The same block periodic along x only: the faces across y and z are free
    // surfaces, so their particles miss neighbours, while x is still seamless.
    let mut open = block(r#""x""#, [0.0; 3]);
    open.step().unwrap();
    let p = open.read(&["density"]);
    let rho = p.channel("density").and_then(|v| v.as_scalars()).unwrap();
    let inner = |x: &[f32; 3]| [x[1], x[2]].iter().all(|&c| c > 2.0 * SPACING && c < SIDE - 2.0 * SPACING);
    for (x, &r) in p.positions.iter().zip(rho) {
        if inner(x) {
            assert!((r - 1000.0).abs() < 0.01, "interior particle at {x:?} has density {r}");
        } else if x[1] < SPACING && x[2] < SPACING {
            assert!(r < 800.0, "corner particle at {x:?} has density {r}: it saw images along y or z");
        }
    }
}

#[test]
fn uniform_flow_wraps_through_the_faces_undisturbed() {
    let v = [1.0, -0.5, 0.25];
    let mut sim = block(r#""x", "y", "z""#, v);
    let start = sim.read(&[]).positions;
    sim.run_until(0.5, |_, _| {}).unwrap();
    let t = sim.time() as f32;
    let end = sim.read(&["velocity", "density"]);
    let wrap = Periodicity::new(sim.domain(), [true; 3]);
    for ((x0, x1), u) in
        start.iter().zip(&end.positions).zip(end.channel("velocity").and_then(|c| c.as_vectors()).unwrap())
    {
        for a in 0..3 {
            assert!((u[a] - v[a]).abs() < 1e-4, "velocity {u:?}, expected {v:?}");
        }
        // Where the particle should be, `t v` on, brought back into the box.
        let moved = glam::Vec3::from(*x0) + glam::Vec3::from(v) * t;
        let miss = wrap.image(glam::Vec3::from(*x1) - wrap.wrap(moved)).length();
        assert!(miss < 1e-4, "particle from {x0:?} is {miss} m from where the flow took it");
        assert!(sim.domain().contains(glam::Vec3::from(*x1)), "{x1:?} outside the box");
    }
    // Every particle crossed at least one face (1 m/s for 0.5 s in a 0.4 m box).
    assert!(t >= 0.5);
}

#[test]
fn scenes_that_cannot_be_periodic_are_refused_naming_the_field() {
    let refuse = |text: &str, field: &str, words: &str| {
        let e = from_str(text, Format::Toml, &[]).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains(words), "{e}");
    };
    let fluid = "particle_spacing = 0.05\n[[fluids]]\nblocks = [{ min = [0, 0, 0], max = [0.4, 0.4, 0.4] }]\n";
    refuse(&format!("periodic = [\"x\"]\n{fluid}"), "periodic", "explicit domain");
    refuse(
        &format!("periodic = [\"x\", \"x\"]\ndomain = {{ min = [0, 0, 0], max = [0.4, 0.4, 0.4] }}\n{fluid}"),
        "periodic[1]",
        "twice",
    );
    refuse(
        &format!("periodic = [\"y\"]\ndomain = {{ min = [0, 0, 0], max = [0.4, 0.15, 0.4] }}\n{fluid}"),
        "domain",
        "shorter than two kernel supports",
    );
    let walls = |open: &str, max_x: f32| {
        format!(
            "periodic = [\"x\"]\ndomain = {{ min = [0, -0.2, -0.2], max = [0.4, 0.6, 0.6] }}\n{fluid}\
             [[boundaries]]\nkind = \"box\"\nmin = [0, 0, 0]\nmax = [{max_x}, 0.4, 0.4]\nopen = [{open}]\n"
        )
    };
    refuse(&walls("", 0.4), "boundaries[0].open", "\"-x\" and \"+x\"");
    refuse(&walls("\"-x\", \"+x\"", 0.3), "boundaries[0]", "span the domain");
    assert!(from_str(&walls("\"-x\", \"+x\"", 0.4), Format::Toml, &[]).is_ok());
    refuse(
        &format!(
            "periodic = [\"z\"]\ndomain = {{ min = [0, -0.2, 0], max = [0.4, 0.6, 0.4] }}\n{fluid}\
             [[boundaries]]\nkind = \"plane\"\ncenter = [0.2, 0, 0.2]\nnormal = [0, 1, 0]\nsize = [0.4, 0.4]\n"
        ),
        "boundaries[0]",
        "not planes",
    );
}

/// A channel between two plates, periodic along the flow: the walls tile the period
/// and fluid next to them near the periodic faces sees the same wall as in the middle.
#[test]
fn walls_across_a_periodic_face_are_seamless() {
    let text = r#"
        particle_spacing = 0.05
        gravity = [0, 0, 0]
        periodic = ["x", "z"]
        domain = { min = [0, -0.3, 0], max = [0.4, 0.7, 0.4] }
        [[fluids]]
        blocks = [{ min = [0, 0, 0], max = [0.4, 0.4, 0.4] }]
        [[boundaries]]
        kind = "box"
        min = [0, 0, 0]
        max = [0.4, 0.4, 0.4]
        open = ["-x", "+x", "-z", "+z"]
        [solver]
        speed_of_sound = 20
    "#;
    let mut sim = Simulation::new_cpu(from_str(text, Format::Toml, &[]).unwrap()).unwrap();
    sim.step().unwrap();
    let p = sim.read(&["density"]);
    let rho = p.channel("density").and_then(|v| v.as_scalars()).unwrap();
    let (lo, hi) = rho.iter().fold((f32::MAX, f32::MIN), |(l, h), &r| (l.min(r), h.max(r)));
    // A flat wall sampled on the lattice gives its neighbours exactly the rest
    // density (boundary.rs), so the whole channel is at rest density.
    assert!((lo - 1000.0).abs() < 0.5 && (hi - 1000.0).abs() < 0.5, "density between {lo} and {hi}");
}
