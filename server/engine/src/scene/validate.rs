//! Validation of a deserialised [`Scene`]: every bound a field must respect,
//! reported as `path: must be ..., got ...`, all errors at once.

use super::{Boundary, EquationOfState, ModuleKind, Scene, TimeStep, Viscosity};

/// The most fluid particles one scene may create (a guard against requests that
/// would exhaust memory: about 100 bytes each on the CPU backend).
pub const MAX_PARTICLES: f64 = 50e6;

struct Checker {
    errors: Vec<String>,
}

impl Checker {
    fn fail(&mut self, path: &str, message: String) {
        self.errors.push(format!("{path}: {message}"));
    }

    fn finite(&mut self, path: &str, v: f32) -> bool {
        if !v.is_finite() {
            self.fail(path, format!("must be a finite number, got {v}"));
        }
        v.is_finite()
    }

    fn positive(&mut self, path: &str, v: f32) {
        if self.finite(path, v) && v <= 0.0 {
            self.fail(path, format!("must be > 0, got {v}"));
        }
    }

    fn non_negative(&mut self, path: &str, v: f32) {
        if self.finite(path, v) && v < 0.0 {
            self.fail(path, format!("must be >= 0, got {v}"));
        }
    }

    fn within(&mut self, path: &str, v: f32, lo: f32, hi: f32) {
        if self.finite(path, v) && !(lo..=hi).contains(&v) {
            self.fail(path, format!("must be between {lo} and {hi}, got {v}"));
        }
    }

    fn vector(&mut self, path: &str, v: &[f32]) {
        for (i, &c) in v.iter().enumerate() {
            self.finite(&format!("{path}[{i}]"), c);
        }
    }

    /// `min < max` on every axis.
    fn ordered_box(&mut self, path: &str, min: [f32; 3], max: [f32; 3]) {
        self.vector(&format!("{path}.min"), &min);
        self.vector(&format!("{path}.max"), &max);
        for (axis, (lo, hi)) in ["x", "y", "z"].iter().zip(min.iter().zip(max)) {
            if lo.is_finite() && hi.is_finite() && hi <= *lo {
                self.fail(
                    &format!("{path}.max"),
                    format!("must exceed min on every axis, got max.{axis} = {hi} <= min.{axis} = {lo}"),
                );
            }
        }
    }
}

/// Checks every field; returns one message per problem.
pub fn validate(scene: &Scene) -> Result<(), Vec<String>> {
    let mut c = Checker { errors: Vec::new() };
    c.positive("particle_spacing", scene.particle_spacing);
    c.vector("gravity", &scene.gravity);
    check_modules(&mut c, scene);
    check_fluids(&mut c, scene);
    for (i, b) in scene.boundaries.iter().enumerate() {
        let path = format!("boundaries[{i}]");
        match b {
            Boundary::Box { min, max, layers, .. } => {
                c.ordered_box(&path, *min, *max);
                c.within(&format!("{path}.layers"), *layers as f32, 1.0, 4.0);
            }
            Boundary::Plane { center, normal, size, layers } => {
                c.vector(&format!("{path}.center"), center);
                c.vector(&format!("{path}.normal"), normal);
                if glam::Vec3::from(*normal).length_squared() < 1e-12 {
                    c.fail(&format!("{path}.normal"), "must be a non-zero vector".into());
                }
                c.positive(&format!("{path}.size[0]"), size[0]);
                c.positive(&format!("{path}.size[1]"), size[1]);
                c.within(&format!("{path}.layers"), *layers as f32, 1.0, 4.0);
            }
        }
    }
    if let Some(d) = &scene.domain {
        c.ordered_box("domain", d.min, d.max);
    }
    check_solver(&mut c, scene);
    c.positive("guard.max_compression", scene.guard.max_compression);
    if let Some(v) = scene.guard.max_speed {
        c.positive("guard.max_speed", v);
    }
    if c.errors.is_empty() { Ok(()) } else { Err(c.errors) }
}

fn check_modules(c: &mut Checker, scene: &Scene) {
    for (i, m) in scene.modules.iter().enumerate() {
        if scene.modules[..i].contains(m) {
            c.fail(&format!("modules[{i}]"), format!("{m:?} is listed twice"));
        }
    }
    let has_fluid = scene.modules.contains(&ModuleKind::Fluid);
    if has_fluid && scene.fluids.is_empty() {
        c.fail("fluids", "must hold at least one fluid, since modules lists \"fluid\"".into());
    }
    if !has_fluid && !scene.fluids.is_empty() {
        c.fail("modules", "must list \"fluid\", since the scene has fluids".into());
    }
    if scene.modules.is_empty() {
        c.fail("modules", "must list at least one module".into());
    }
}

fn check_fluids(c: &mut Checker, scene: &Scene) {
    if scene.fluids.len() > 1 {
        c.fail("fluids", format!("one fluid phase is supported, got {}", scene.fluids.len()));
    }
    let mut particles = 0.0f64;
    for (i, f) in scene.fluids.iter().enumerate() {
        let p = format!("fluids[{i}]");
        c.positive(&format!("{p}.rest_density"), f.rest_density);
        match f.eos {
            EquationOfState::Tait { gamma } => c.within(&format!("{p}.eos.gamma"), gamma, 1.0, 10.0),
            EquationOfState::Linear { stiffness: Some(k) } => c.positive(&format!("{p}.eos.stiffness"), k),
            EquationOfState::Linear { stiffness: None } => {}
        }
        match f.viscosity {
            Viscosity::None => {}
            Viscosity::Laplacian { nu } => c.non_negative(&format!("{p}.viscosity.nu"), nu),
            Viscosity::Artificial { alpha } => c.within(&format!("{p}.viscosity.alpha"), alpha, 0.0, 1.0),
        }
        c.within(&format!("{p}.xsph"), f.xsph, 0.0, 1.0);
        if f.blocks.is_empty() {
            c.fail(&format!("{p}.blocks"), "must hold at least one block".into());
        }
        for (j, b) in f.blocks.iter().enumerate() {
            let bp = format!("{p}.blocks[{j}]");
            c.ordered_box(&bp, b.min, b.max);
            c.vector(&format!("{bp}.velocity"), &b.velocity);
            if scene.particle_spacing > 0.0 {
                let n: f64 =
                    (0..3).map(|a| ((b.max[a] - b.min[a]) as f64 / scene.particle_spacing as f64).max(0.0)).product();
                particles += n;
            }
        }
    }
    if particles > MAX_PARTICLES {
        c.fail("fluids", format!("would create {particles:.3e} particles, more than the limit of {MAX_PARTICLES:.0e}; increase particle_spacing"));
    }
}

fn check_solver(c: &mut Checker, scene: &Scene) {
    let s = &scene.solver;
    c.within("solver.support_factor", s.support_factor, 1.2, 4.0);
    if let Some(v) = s.speed_of_sound {
        c.positive("solver.speed_of_sound", v);
    }
    c.within("solver.mach_factor", s.mach_factor, 1.0, 1000.0);
    if let Some(v) = s.expected_max_speed {
        c.positive("solver.expected_max_speed", v);
    }
    c.non_negative("solver.damping", s.damping);
    c.non_negative("solver.damping_until", s.damping_until);
    match s.time_step {
        TimeStep::Adaptive { cfl, min, max } => {
            c.within("solver.time_step.cfl", cfl, 1e-3, 2.0);
            c.positive("solver.time_step.min", min);
            c.positive("solver.time_step.max", max);
            if max < min {
                c.fail("solver.time_step.max", format!("must be >= min ({min}), got {max}"));
            }
        }
        TimeStep::Fixed { dt, cfl } => {
            c.positive("solver.time_step.dt", dt);
            c.within("solver.time_step.cfl", cfl, 1e-3, 2.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::load::from_preset;

    fn errors(overrides: &[&str]) -> String {
        let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        from_preset("dam_break", &o).unwrap_err().to_string()
    }

    #[test]
    fn every_bad_field_is_named() {
        assert_eq!(errors(&["particle_spacing=0"]), "particle_spacing: must be > 0, got 0");
        assert!(
            errors(&["fluids[0].blocks[0].max=[0,1,1]"])
                .contains("fluids[0].blocks[0].max: must exceed min on every axis, got max.x = 0 <= min.x = 0")
        );
        assert_eq!(
            errors(&["solver.time_step.max=1e-9"]),
            "solver.time_step.max: must be >= min (0.0000001), got 0.000000001"
        );
        assert_eq!(
            errors(&["fluids[0].viscosity={\"model\":\"artificial\",\"alpha\":3}"]),
            "fluids[0].viscosity.alpha: must be between 0 and 1, got 3"
        );
        assert!(errors(&["particle_spacing=1e-5"]).starts_with("fluids: would create"));
        assert_eq!(
            errors(&["modules=[]"]),
            "modules: must list \"fluid\", since the scene has fluids\nmodules: must list at least one module"
        );
        // Several problems are reported together.
        let both = errors(&["particle_spacing=-1", "guard.max_compression=0"]);
        assert_eq!(both.lines().count(), 2, "{both}");
    }
}
