//! Which scene fields may change while a scene runs, and applying such changes.
//!
//! Tunable: `gravity`, `fluids[0].viscosity`, `fluids[0].xsph`,
//! `solver.time_step`, `solver.damping`, `solver.damping_until` and `guard`.
//! Everything else (resolution, geometry, kernel, equation of state, ...) shapes
//! the particles and buffers themselves and needs a new scene.

use super::Scene;
use super::load::{SceneError, apply_overrides, from_value};

/// The tunable fields, as written in overrides.
pub const TUNABLE: &[&str] = &[
    "gravity",
    "fluids[0].viscosity",
    "fluids[0].xsph",
    "solver.time_step",
    "solver.damping",
    "solver.damping_until",
    "guard",
];

/// `next` with every tunable field taken from `current`.
fn structure(next: &Scene, current: &Scene) -> Scene {
    let mut s = next.clone();
    s.gravity = current.gravity;
    if let (Some(a), Some(b)) = (s.fluids.get_mut(0), current.fluids.first()) {
        a.viscosity = b.viscosity;
        a.xsph = b.xsph;
    }
    s.solver.time_step = current.solver.time_step;
    s.solver.damping = current.solver.damping;
    s.solver.damping_until = current.solver.damping_until;
    s.guard = current.guard;
    s
}

/// Applies `key=value` overrides to a running scene: the new scene, validated,
/// or an error naming a field that cannot change while the scene runs.
pub fn apply(current: &Scene, overrides: &[String]) -> Result<Scene, SceneError> {
    let mut value = serde_json::to_value(current).expect("scenes serialise");
    apply_overrides(&mut value, overrides)?;
    let next = from_value(value)?;
    if structure(&next, current) != *current {
        let keys: Vec<&str> = overrides.iter().map(|o| o.split('=').next().unwrap_or(o).trim()).collect();
        return Err(SceneError::Invalid(vec![format!(
            "{}: cannot change while the scene exists; tunable fields are {}",
            keys.join(", "),
            TUNABLE.join(", ")
        )]));
    }
    Ok(next)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::presets;

    #[test]
    fn tunable_fields_change_and_others_are_refused() {
        let scene = presets::dam_break();
        let next = apply(&scene, &["gravity=[0,-1,0]".into(), "fluids[0].xsph=0.2".into()]).unwrap();
        assert_eq!(next.gravity, [0.0, -1.0, 0.0]);
        assert_eq!(next.fluids[0].xsph, 0.2);
        let e = apply(&scene, &["particle_spacing=0.01".into()]).unwrap_err().to_string();
        assert!(e.starts_with("particle_spacing: cannot change while the scene exists"), "{e}");
        let e = apply(&scene, &["fluids[0].xsph=7".into()]).unwrap_err().to_string();
        assert_eq!(e, "fluids[0].xsph: must be between 0 and 1, got 7");
    }
}
