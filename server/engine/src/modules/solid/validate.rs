//! The `solid` section's checks: each names the setting it rejects and why.

use super::{MAX_COLOURS, MAX_ITERATIONS, SECTION, spec};
use crate::scene::Scene;
use crate::scene::validate::Checker;

/// Checks a scene's `solid` section, where it has one.
pub(super) fn validate(scene: &Scene, c: &mut Checker) {
    let Some(s) = scene.section::<spec::Solid>(SECTION) else { return };
    if s.bodies.is_empty() {
        c.fail("solid.bodies", "name at least one fluid".into());
    }
    for (i, b) in s.bodies.iter().enumerate() {
        c.vector(&format!("solid.bodies[{i}].angular_velocity"), &b.angular_velocity);
    }
    c.within("solid.cluster_radius", s.cluster_radius, 1.0, 4.0);
    if let Some(d) = s.centre_spacing {
        // A particle left out of every centre's reach would belong to no cluster.
        c.within("solid.centre_spacing", d, 1.0, s.cluster_radius);
    }
    c.within("solid.stiffness", s.stiffness, 0.0, 1.0);
    c.within("solid.damping", s.damping, 0.0, 1.0);
    if !(1..=MAX_ITERATIONS).contains(&s.iterations) {
        c.fail("solid.iterations", format!("must be between 1 and {MAX_ITERATIONS}, got {}", s.iterations));
    }
    if !(2..=MAX_COLOURS).contains(&s.colours) {
        c.fail("solid.colours", format!("must be between 2 and {MAX_COLOURS}, got {}", s.colours));
    }
    if let Some(o) = &s.oriented {
        for (k, r) in o.radii.iter().enumerate() {
            c.within(&format!("solid.oriented.radii[{k}]"), *r, 0.0, 4.0);
        }
    }
    bodies_fit(scene, &s, c);
}

/// Each elastic body's block lies inside the scene's domain (or a box of walls,
/// where the domain follows the particles) and overlaps no other body's block:
/// particles of two bodies on one lattice point would be one cluster's members
/// twice over.
fn bodies_fit(scene: &Scene, s: &spec::Solid, c: &mut Checker) {
    /// What this check reads of a fluid (the fluid module's section, read as
    /// data: a module does not use another's types).
    #[derive(serde::Deserialize)]
    struct Extent {
        min: [f32; 3],
        max: [f32; 3],
    }
    #[derive(serde::Deserialize)]
    struct Body {
        name: String,
        #[serde(default)]
        blocks: Vec<Extent>,
    }
    let all: Vec<Body> = scene.section("fluids").unwrap_or_default();
    let fluids: Vec<(usize, Body)> =
        all.into_iter().enumerate().filter(|(_, f)| s.bodies.iter().any(|b| b.fluid == f.name)).collect();
    let rooms: Vec<([f32; 3], [f32; 3])> = match &scene.domain {
        Some(d) => vec![(d.min, d.max)],
        None => scene
            .boundaries
            .iter()
            .filter_map(|b| match b {
                crate::scene::Boundary::Box { min, max, .. } => Some((*min, *max)),
                _ => None,
            })
            .collect(),
    };
    let inside = |lo: [f32; 3], hi: [f32; 3], room: &([f32; 3], [f32; 3])| {
        (0..3).all(|k| lo[k] >= room.0[k] && hi[k] <= room.1[k])
    };
    let mut blocks: Vec<(String, [f32; 3], [f32; 3])> = Vec::new();
    for (i, f) in &fluids {
        for (j, b) in f.blocks.iter().enumerate() {
            let path = format!("fluids[{i}].blocks[{j}]");
            if !rooms.is_empty() && !rooms.iter().any(|r| inside(b.min, b.max, r)) {
                c.fail(&path, "an elastic body must lie inside the domain (or a box of walls)".into());
            }
            if let Some((other, _, _)) =
                blocks.iter().find(|(_, lo, hi)| (0..3).all(|k| b.min[k] < hi[k] && lo[k] < b.max[k]))
            {
                c.fail(&path, format!("overlaps {other}: elastic bodies may touch but not overlap"));
            }
            blocks.push((path, b.min, b.max));
        }
    }
}
