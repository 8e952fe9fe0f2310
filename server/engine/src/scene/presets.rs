//! Built-in scenes. Each is an ordinary [`Scene`] value, so `--set` overrides and
//! `floe schema` apply to them exactly as to files.

use super::{Boundary, BoxRegion, Fluid, FluidBlock, Scene, Solver, Viscosity};

/// Names of the built-in presets.
pub const NAMES: &[&str] = &["dam_break", "hydrostatic"];

/// The preset called `name`.
pub fn get(name: &str) -> Option<Scene> {
    match name {
        "dam_break" => Some(dam_break()),
        "hydrostatic" => Some(hydrostatic()),
        _ => None,
    }
}

/// Column width a (m) of the dam break.
pub const DAM_BREAK_A: f32 = 0.5;

fn water(blocks: Vec<FluidBlock>, viscosity: Viscosity) -> Fluid {
    Fluid { name: "water".into(), rest_density: 1000.0, eos: Default::default(), viscosity, xsph: 0.0, blocks }
}

fn block(min: [f32; 3], max: [f32; 3]) -> FluidBlock {
    FluidBlock { min, max, velocity: [0.0; 3] }
}

fn closed_box(min: [f32; 3], max: [f32; 3]) -> Boundary {
    Boundary::Box { min, max, open: Vec::new(), layers: 1 }
}

/// Koshizuka & Oka (1996) / Martin & Moyce (1952) dam break: a water column
/// a wide and 2a high (a = 0.5 m), a/2 deep, against the left wall of a tank
/// 4a x 2.4a x a/2. Spacing a/28 gives 21,952 fluid particles.
pub fn dam_break() -> Scene {
    let a = DAM_BREAK_A;
    Scene {
        name: "dam_break".into(),
        modules: vec![super::ModuleKind::Fluid],
        particle_spacing: a / 28.0,
        gravity: [0.0, -9.81, 0.0],
        fluids: vec![water(vec![block([0.0; 3], [a, 2.0 * a, 0.5 * a])], Viscosity::Artificial { alpha: 0.02 })],
        boundaries: vec![closed_box([0.0; 3], [4.0 * a, 2.4 * a, 0.5 * a])],
        domain: None,
        solver: Solver::default(),
        guard: Default::default(),
    }
}

/// Water at rest in a closed tank 0.3 x 1.0 x 0.15 m, filled to H = 0.9 m
/// (the column height of Adami et al. 2012). Damped for its first 0.5 s so it
/// settles; afterwards pressure should match `rho0 g (H - y)`.
pub fn hydrostatic() -> Scene {
    Scene {
        name: "hydrostatic".into(),
        modules: vec![super::ModuleKind::Fluid],
        particle_spacing: 0.025,
        gravity: [0.0, -9.81, 0.0],
        fluids: vec![water(vec![block([0.0; 3], [0.3, 0.9, 0.15])], Viscosity::Artificial { alpha: 0.02 })],
        boundaries: vec![closed_box([0.0; 3], [0.3, 1.0, 0.15])],
        domain: Some(BoxRegion { min: [-0.1, -0.1, -0.1], max: [0.4, 1.1, 0.25] }),
        solver: Solver { damping: 5.0, damping_until: 0.5, ..Solver::default() },
        guard: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid() {
        for name in NAMES {
            let scene = get(name).unwrap();
            crate::scene::validate::validate(&scene).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        }
        assert!(get("nope").is_none());
    }
}
