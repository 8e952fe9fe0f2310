//! Validation of a deserialised [`Scene`]: every bound a field must respect,
//! reported as `path: must be ..., got ...`, all errors at once.

use super::{Boundary, Scene, TimeStep};

/// The most particles one scene may create (a guard against requests that would
/// exhaust memory: under 300 bytes each on the CPU backend, `floe bench --memory`).
pub const MAX_PARTICLES: f64 = 50e6;

/// Collects validation errors, each as `path: message`. Modules use it to check
/// their sections.
#[derive(Debug, Default)]
pub struct Checker {
    errors: Vec<String>,
}

impl Checker {
    /// The errors recorded.
    pub fn into_errors(self) -> Vec<String> {
        self.errors
    }

    /// Records that the field at `path` is wrong.
    pub fn fail(&mut self, path: &str, message: String) {
        self.errors.push(format!("{path}: {message}"));
    }

    /// Checks that `v` is finite.
    pub fn finite(&mut self, path: &str, v: f32) -> bool {
        if !v.is_finite() {
            self.fail(path, format!("must be a finite number, got {v}"));
        }
        v.is_finite()
    }

    /// Checks `v > 0`.
    pub fn positive(&mut self, path: &str, v: f32) {
        if self.finite(path, v) && v <= 0.0 {
            self.fail(path, format!("must be > 0, got {v}"));
        }
    }

    /// Checks `v >= 0`.
    pub fn non_negative(&mut self, path: &str, v: f32) {
        if self.finite(path, v) && v < 0.0 {
            self.fail(path, format!("must be >= 0, got {v}"));
        }
    }

    /// Checks `lo <= v <= hi`.
    pub fn within(&mut self, path: &str, v: f32, lo: f32, hi: f32) {
        if self.finite(path, v) && !(lo..=hi).contains(&v) {
            self.fail(path, format!("must be between {lo} and {hi}, got {v}"));
        }
    }

    /// Checks every component is finite.
    pub fn vector(&mut self, path: &str, v: &[f32]) {
        for (i, &c) in v.iter().enumerate() {
            self.finite(&format!("{path}[{i}]"), c);
        }
    }

    /// Checks `min < max` on every axis.
    pub fn ordered_box(&mut self, path: &str, min: [f32; 3], max: [f32; 3]) {
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
    for m in crate::module::of(scene) {
        (m.validate)(scene, &mut c);
    }
    if c.errors.is_empty() {
        // Claims parse the sections: only once they are valid.
        crate::quantities::check(scene, &mut c);
    }
    let counted = scene.particle_spacing.is_finite() && scene.particle_spacing > 0.0;
    let counts = crate::module::counts(scene);
    let particles = counts.iter().map(|(_, n)| *n).fold(0, u64::saturating_add);
    if counted && particles as f64 > MAX_PARTICLES {
        let each: Vec<String> = counts.iter().map(|(space, n)| format!("{space} {n}")).collect();
        c.fail(
            "particle_spacing",
            format!(
                "the scene would create {particles} particles and elements ({}), more than the limit of {MAX_PARTICLES:.0e}; \
                 increase particle_spacing or shrink the largest",
                each.join(", ")
            ),
        );
    }
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
            Boundary::Terrain(t) => t.validate(&mut c, &path, scene.particle_spacing),
        }
    }
    if let Some(d) = &scene.domain {
        c.ordered_box("domain", d.min, d.max);
    }
    check_periodic(&mut c, scene);
    check_solver(&mut c, scene);
    c.positive("guard.max_compression", scene.guard.max_compression);
    if let Some(v) = scene.guard.max_speed {
        c.positive("guard.max_speed", v);
    }
    if c.errors.is_empty() { Ok(()) } else { Err(c.errors) }
}

/// A periodic axis has an explicit domain at least two kernel supports long (so each
/// pair within the support has one image), and walls do not close it.
fn check_periodic(c: &mut Checker, scene: &Scene) {
    use super::{Axis, Face};
    for (i, a) in scene.periodic.iter().enumerate() {
        if scene.periodic[..i].contains(a) {
            c.fail(&format!("periodic[{i}]"), format!("axis {} is listed twice", a.name()));
        }
    }
    if scene.periodic.is_empty() {
        return;
    }
    let Some(domain) = &scene.domain else {
        c.fail("periodic", "needs an explicit domain: its extent along a periodic axis is the period".into());
        return;
    };
    let support = scene.solver.support_factor * scene.particle_spacing;
    let faces = |a: Axis| match a {
        Axis::X => [Face::MinusX, Face::PlusX],
        Axis::Y => [Face::MinusY, Face::PlusY],
        Axis::Z => [Face::MinusZ, Face::PlusZ],
    };
    for &a in &scene.periodic {
        let (axis, k) = (a.name(), a.index());
        let period = domain.max[k] - domain.min[k];
        if support.is_finite() && period < 2.0 * support {
            c.fail(
                "domain",
                format!(
                    "the period along the periodic axis {axis} is {period} m, shorter than two kernel supports \
                     (2 x {support} m); widen the domain along {axis}"
                ),
            );
        }
        for (i, b) in scene.boundaries.iter().enumerate() {
            let path = format!("boundaries[{i}]");
            match b {
                Boundary::Plane { .. } | Boundary::Terrain(_) => c.fail(
                    &path,
                    format!("a scene periodic along {axis} takes box walls open across {axis}, not planes or terrains"),
                ),
                Boundary::Box { min, max, open, .. } => {
                    if !faces(a).iter().all(|f| open.contains(f)) {
                        c.fail(
                            &format!("{path}.open"),
                            format!("must list \"-{axis}\" and \"+{axis}\": the scene is periodic along {axis}"),
                        );
                    }
                    if min[k] != domain.min[k] || max[k] != domain.max[k] {
                        c.fail(
                            &path,
                            format!(
                                "must span the domain along the periodic axis {axis} (min.{axis} = {}, max.{axis} = {}), \
                                 got {} to {}",
                                domain.min[k], domain.max[k], min[k], max[k]
                            ),
                        );
                    }
                }
            }
        }
    }
}

/// Every listed module exists, once, with its section and its requirements; every
/// section present belongs to a listed module.
fn check_modules(c: &mut Checker, scene: &Scene) {
    let names: Vec<&str> = crate::module::all().iter().map(|m| m.id).collect();
    for (i, m) in scene.modules.iter().enumerate() {
        let path = format!("modules[{i}]");
        if scene.modules[..i].contains(m) {
            c.fail(&path, format!("{:?} is listed twice", m));
        }
        match crate::module::find(m) {
            None => c.fail(&path, format!("unknown module {:?}; modules are {}", m, names.join(", "))),
            Some(def) => {
                for r in def.requires {
                    if !scene.modules.iter().any(|x| x == r) {
                        c.fail(&path, format!("{m:?} requires module {r:?}, which the scene does not list"));
                    }
                }
            }
        }
    }
    for def in crate::module::all() {
        let Some(section) = def.section else { continue };
        let listed = scene.modules.iter().any(|m| m == def.id);
        match (listed, scene.sections.has(section.key())) {
            (true, false) => {
                if let Some(missing) = section.missing {
                    c.fail(section.key(), missing.into());
                }
            }
            (false, true) => {
                c.fail("modules", format!("must list {:?}, since the scene has its section {}", def.id, section.key()))
            }
            _ => {}
        }
    }
    if scene.modules.is_empty() {
        c.fail("modules", "must list at least one module".into());
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
    match crate::scheme::find(&s.method) {
        None => {
            let known: Vec<&str> = crate::scheme::all().iter().map(|d| d.id).collect();
            c.fail("solver.method", format!("unknown scheme {:?}; schemes are {}", s.method, known.join(", ")));
        }
        Some(_) => {
            // Every scheme checks its settings, and refuses them in a scene of another.
            for d in crate::scheme::all() {
                (d.validate)(scene, d.id == s.method, c);
            }
        }
    }
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
        // The block is named first (fluid's check), then the scene's count (the core's).
        let e = errors(&["particle_spacing=1e-5"]);
        assert!(e.starts_with("fluids[0].blocks[0]: its box holds"), "{e}");
        assert!(e.contains("\nparticle_spacing: the scene would create"), "{e}");
        assert_eq!(
            errors(&["modules=[]"]),
            "modules: must list \"fluid\", since the scene has its section fluids\nmodules: must list at least one module"
        );
        // A scene without fluids is told what its file lacks, by the key it spells.
        assert_eq!(errors(&["fluids=[]"]), "fluids: at least one fluid is required");
        assert_eq!(
            errors(&["modules=[\"fluid\",\"lava\"]"]),
            "modules[1]: unknown module \"lava\"; modules are fluid, heat, snow, snowfall, solid"
        );
        assert_eq!(
            errors(&["fluids[0].eos={\"kind\":\"tait\",\"background\":-1}"]),
            "fluids[0].eos.background: must be >= 0, got -1"
        );
        assert_eq!(
            errors(&["fluids[0].blocks[0].taylor_green={\"amplitude\":1,\"wavelength\":0}"]),
            "fluids[0].blocks[0].taylor_green.wavelength: must be > 0, got 0"
        );
        assert_eq!(
            errors(&["solver.transport_velocity={\"background\":-5}", "solver.method=\"dfsph\""]),
            "solver.transport_velocity.background: must be > 0, got -5\n\
             solver.transport_velocity: works with solver.method = \"wcsph\" only"
        );
        assert_eq!(
            errors(&["solver.delta_sph={\"delta\":1.5}", "solver.method=\"dfsph\""]),
            "solver.delta_sph.delta: must be between 0 and 1, got 1.5\n\
             solver.delta_sph: works with solver.method = \"wcsph\" only"
        );
        assert_eq!(
            errors(&["solver.integrator=\"leapfrog\"", "solver.method=\"dfsph\""]),
            "solver.integrator: works with solver.method = \"wcsph\" only"
        );
        assert_eq!(
            errors(&["solver.dfsph.compact_gradients=true", "solver.kernel=\"mueller\""]),
            "solver.dfsph.compact_gradients: needs solver.kernel = \"cubic_spline\" or \"wendland_c2\" \
             (the spiky gradient over r is unbounded near r = 0)"
        );
        // Several problems are reported together.
        let both = errors(&["particle_spacing=-1", "guard.max_compression=0"]);
        assert_eq!(both.lines().count(), 2, "{both}");
    }
}
