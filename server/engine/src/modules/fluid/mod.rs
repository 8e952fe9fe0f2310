//! The fluid module: fluid phases as materials, sampled from blocks; viscosity
//! (Laplacian or Monaghan's artificial); XSPH; gravity; and, fused into the same
//! neighbour loop when the scheme is WCSPH, the pressure force.
//!
//! - [`spec`]: the scene section (`fluids`).
//! - [`viscosity`]: the pairwise viscous terms. (Viscosity that varies from
//!   particle to particle, set by another module, is the core's:
//!   [`crate::viscosity`].)
//! - [`forces`]: the force pass; [`xsph`]: the XSPH passes.
//! - [`presets`]: `dam_break`, `hydrostatic`.
//! - [`cases`]: validation cases and the stability battery.

pub mod cases;
pub mod forces;
pub mod presets;
pub mod spec;
pub mod viscosity;
pub mod xsph;

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::kernel::Kernel;
use crate::materials::{Material, MaterialKind, per_material};
use crate::math::{Aabb, Real, Vec3};
use crate::model::{BuildError, Model, ModelBuilder};
use crate::module::{ModuleDef, Section};
use crate::quantities::{Claim, Write};
use crate::sampling::{box_count, fill_box};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
use crate::scene::validate::Checker;
use spec::Viscosity;
use viscosity::ViscosityModel;

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "fluid",
    about: "SPH fluid phases: materials sampled from blocks, viscosity, XSPH, gravity.",
    requires: &[],
    section: Some(Section {
        def: SectionDef::of::<Vec<spec::Fluid>>(SECTION),
        missing: Some("at least one fluid is required"),
    }),
    validate,
    count,
    materials: |scene| fluids(scene).len(),
    claims,
    particles,
    build,
    retune,
    tunables: TUNABLES,
    cpu: &[("fluid.forces", &forces::Forces), ("fluid.xsph", &xsph::Xsph), ("fluid.xsph_kick", &xsph::XsphKick)],
    presets: presets::PRESETS,
    dt_limit,
    measures,
    cases: cases::CASES,
    stability: cases::STABILITY,
    bench: &[],
};

/// The module's section of a scene: `fluids`, a list of [`spec::Fluid`].
pub const SECTION: &str = "fluids";

/// The scene's fluids (none if it has no `fluids` section).
pub fn fluids(scene: &Scene) -> Vec<spec::Fluid> {
    scene.section(SECTION).unwrap_or_default()
}

/// A fluid's own viscosity model is its viscosity: a module's law that would set
/// the particles' viscosity (`mu`) for it is refused.
fn claims(scene: &Scene) -> Vec<Claim> {
    let own = |(i, f): (usize, &spec::Fluid)| {
        (f.viscosity != Viscosity::None).then(|| Claim {
            material: i,
            path: format!("{SECTION}[{i}].viscosity"),
            write: Write::Own,
            fix: r#"must be {"model": "none"}"#,
        })
    };
    fluids(scene).iter().enumerate().filter_map(own).collect()
}

/// The module's live settings.
pub const TUNABLES: &[Tunable] = &[
    Tunable {
        path: "fluids[*].viscosity",
        unit: "",
        min: None,
        max: None,
        about: "A fluid's viscosity model: {\"model\": \"laplacian\", \"nu\": m^2/s} or {\"model\": \"artificial\", \"alpha\": 0 to 1}.",
        module: "fluid",
    },
    Tunable {
        path: "fluids[*].xsph",
        unit: "",
        min: Some(0.0),
        max: Some(1.0),
        about: "A fluid's XSPH velocity correction factor (0 switches it off).",
        module: "fluid",
    },
];

/// XSPH velocity corrections (m/s): allocated only while a fluid uses XSPH.
pub static XSPH: AttrSpec = AttrSpec {
    name: "xsph",
    elem: Elem::Vec3,
    unit: "m/s",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "fluid",
    about: "XSPH velocity correction of the last evaluation.",
};

/// The module's constants, per material.
#[derive(Debug, Clone)]
pub struct FluidConsts {
    /// Viscosity of each material.
    pub viscosity: Vec<ViscosityModel>,
    /// Viscosity between materials `a` and `b`, at `a * materials + b` (see [`ViscosityModel::mix`]).
    pub pair_viscosity: Vec<ViscosityModel>,
    /// XSPH factor epsilon of each material (0 = off).
    pub xsph: Vec<Real>,
    /// Mass ratios `m_a / m_b` at `a * materials + b`, for the multi-material pressure term.
    pub mass_ratio: Vec<Real>,
}

impl FluidConsts {
    /// The constants of `scene`'s fluids made of `materials`, in a scene whose speed
    /// of sound is `c`: each fluid's artificial viscosity scales with its own speed
    /// ([`crate::materials::EquationOfState::sound_speed`]).
    fn new(scene: &Scene, materials: &[Material], c: Real, kernel: &Kernel, spacing: Real) -> Self {
        let n = materials.len();
        // Each fluid's from its own material, then one per material (a phase takes
        // its fluid's).
        let own: Vec<ViscosityModel> = fluids(scene)
            .iter()
            .zip(materials)
            .map(|(f, m)| ViscosityModel::new(f.viscosity, m.rest_density, f.eos.sound_speed(c), kernel, spacing))
            .collect();
        let viscosity = per_material(materials, &own);
        let mut pair_viscosity = Vec::with_capacity(n * n);
        let mut mass_ratio = Vec::with_capacity(n * n);
        for a in 0..n {
            for b in 0..n {
                pair_viscosity.push(if a == b { viscosity[a] } else { viscosity[a].mix(&viscosity[b]) });
                mass_ratio.push(materials[a].mass / materials[b].mass);
            }
        }
        let xsph: Vec<Real> = fluids(scene).iter().map(|f| f.xsph).collect();
        Self { viscosity, pair_viscosity, xsph: per_material(materials, &xsph), mass_ratio }
    }

    /// Whether any material uses XSPH.
    pub fn uses_xsph(&self) -> bool {
        self.xsph.iter().any(|&e| e > 0.0)
    }
}

fn validate(scene: &Scene, c: &mut Checker) {
    for (i, f) in fluids(scene).iter().enumerate() {
        let p = format!("fluids[{i}]");
        c.positive(&format!("{p}.rest_density"), f.rest_density);
        let background = match f.eos {
            spec::EquationOfState::Tait { gamma, background } => {
                c.within(&format!("{p}.eos.gamma"), gamma, 1.0, 10.0);
                background
            }
            spec::EquationOfState::Linear { stiffness, background } => {
                if let Some(k) = stiffness {
                    c.positive(&format!("{p}.eos.stiffness"), k);
                }
                background
            }
        };
        c.non_negative(&format!("{p}.eos.background"), background);
        match f.viscosity {
            Viscosity::None => {}
            Viscosity::Laplacian { nu } => c.non_negative(&format!("{p}.viscosity.nu"), nu),
            Viscosity::Artificial { alpha } => c.within(&format!("{p}.viscosity.alpha"), alpha, 0.0, 1.0),
        }
        c.within(&format!("{p}.xsph"), f.xsph, 0.0, 1.0);
        if f.blocks.is_empty() && !filled(scene).contains(&f.name) {
            c.fail(
                &format!("{p}.blocks"),
                format!(
                    "must hold at least one block: nothing in the scene fills the fluid {:?} while it runs \
                     (a fluid may start empty only when {} names it)",
                    f.name,
                    FILLED_BY.iter().map(|(path, _)| *path).collect::<Vec<_>>().join(" or ")
                ),
            );
        }
        for (j, b) in f.blocks.iter().enumerate() {
            let bp = format!("{p}.blocks[{j}]");
            c.ordered_box(&bp, b.min, b.max);
            c.vector(&format!("{bp}.velocity"), &b.velocity);
            if let Some(tg) = b.taylor_green {
                c.finite(&format!("{bp}.taylor_green.amplitude"), tg.amplitude);
                c.positive(&format!("{bp}.taylor_green.wavelength"), tg.wavelength);
            }
            let d = scene.particle_spacing;
            let points = if d.is_finite() && d > 0.0 { box_count(b.min, b.max, d) } else { 0 };
            if points as f64 > crate::scene::validate::MAX_PARTICLES {
                // Named here, before the mesh is read or anything placed: the core's
                // limit counts the whole scene.
                c.fail(
                    &bp,
                    format!(
                        "its box holds {points} lattice points at particle_spacing {d} (a mesh or shape fills \
                         part of them), more than the limit of {:.0e}; make it smaller or the spacing larger",
                        crate::scene::validate::MAX_PARTICLES
                    ),
                );
            }
            if let Some(mesh) = &b.mesh {
                crate::mesh::validate(c, &format!("{bp}.mesh"), mesh);
                if !b.shape.is_box() {
                    c.fail(
                        &format!("{bp}.shape"),
                        "a block shaped by a mesh cannot also be a sphere or cylinder".into(),
                    );
                }
            }
        }
    }
    // (Without the section at all the registry says so: the module is listed.)
    if scene.sections.has(SECTION) && fluids(scene).is_empty() {
        c.fail(SECTION, "at least one fluid is required".into());
    }
    if fluids(scene).len() > 256 {
        c.fail(SECTION, format!("at most 256 fluid phases, got {}", fluids(scene).len()));
    }
}

/// The settings of other modules' sections that name a fluid something fills while
/// the scene runs, as paths into the scene document (`*`: every element of a list):
/// the snowfall's release creates particles of its `fluid` (`ModelBuilder::emitter`),
/// and heat's melting turns a fluid's particles into a phase like its `into`
/// (`ModelBuilder::phase`). Only such a fluid may start without blocks; any other
/// would stay empty for ever (a scene of 0 particles by mistake). Read as data, as
/// the heat module reads the fluids' names: a module that learns to fill a fluid
/// adds its setting here.
const FILLED_BY: &[(&str, &[&str])] = &[
    ("snowfall.release.fluid", &["snowfall", "release", "fluid"]),
    ("heat.fluids[*].melting.into", &["heat", "fluids", "*", "melting", "into"]),
];

/// The names of the fluids [`FILLED_BY`]'s settings name in `scene`.
fn filled(scene: &Scene) -> Vec<String> {
    fn walk(value: &serde_json::Value, path: &[&str], out: &mut Vec<String>) {
        match path.split_first() {
            None => out.extend(value.as_str().map(String::from)),
            Some((&"*", rest)) => value.as_array().into_iter().flatten().for_each(|v| walk(v, rest, out)),
            Some((key, rest)) => {
                if let Some(v) = value.get(key) {
                    walk(v, rest, out)
                }
            }
        }
    }
    let mut names = Vec::new();
    for (_, path) in FILLED_BY {
        let Some(section) = scene.sections.get::<serde_json::Value>(path[0]) else { continue };
        walk(&section, &path[1..], &mut names);
    }
    names
}

/// How many particles the fluids' blocks hold, counted without placing them (an
/// upper bound where a terrain buries part of a block or a mesh or shape trims it:
/// those outside are dropped at build).
fn count(scene: &Scene) -> Vec<(&'static str, u64)> {
    let blocks = fluids(scene).into_iter().flat_map(|f| f.blocks);
    let n = blocks.map(|b| box_count(b.min, b.max, scene.particle_spacing)).fold(0u64, u64::saturating_add);
    vec![(PARTICLES, n)]
}

/// Each fluid is a material; its blocks are filled on the particle lattice.
fn particles(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let d = scene.particle_spacing;
    for (i, f) in fluids(scene).iter().enumerate() {
        let material = b.material(&f.name, MaterialKind::Fluid, f.rest_density, f.eos, f.look);
        for (j, block) in f.blocks.iter().enumerate() {
            let path = format!("fluids[{i}].blocks[{j}]");
            let bounds = Aabb::new(block.min.into(), block.max.into());
            let pts = match &block.mesh {
                None => {
                    let mut pts = fill_box(block.min, block.max, d);
                    pts.retain(|x| block.shape.holds(block.min, block.max, (*x).into()));
                    pts
                }
                Some(m) => {
                    let mesh = m.load().map_err(|e| BuildError::Mesh(format!("{path}.mesh: {e}")))?;
                    mesh.fitted(bounds).fill_with(m.fill, bounds, d)
                }
            };
            if pts.is_empty() {
                return Err(BuildError::EmptyBlock { path, spacing: d });
            }
            let velocities = pts.iter().map(|x| Vec3::from(block.velocity_at((*x).into()))).collect();
            b.particles(material, pts, velocities, bounds);
        }
    }
    Ok(())
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    // Monaghan's artificial viscosity scales with the speed of sound.
    let artificial = fluids(scene).iter().any(|f| matches!(f.viscosity, Viscosity::Artificial { .. }));
    let c = if artificial { b.sound_speed()? } else { 0.0 };
    let consts = FluidConsts::new(scene, b.materials(), c, &b.kernel, scene.particle_spacing);
    b.pass(if b.scheme().pressure_terms { &forces::WITH_PRESSURE } else { &forces::FORCES });
    if consts.uses_xsph() {
        b.zeros(&XSPH);
        b.pass(&xsph::SUM);
        b.pass(&xsph::KICK);
    }
    b.set_consts(consts);
    Ok(())
}

/// Viscosity and XSPH may change; XSPH's buffer and passes come and go with it.
fn retune(scene: &Scene, model: &mut Model) {
    let c = model.sound_speed.unwrap_or(0.0);
    let consts = FluidConsts::new(scene, model.materials.as_slice(), c, &model.kernel, model.spacing);
    model.toggle(consts.uses_xsph(), &XSPH, &[&xsph::SUM, &xsph::KICK]);
    model.set_consts(consts);
}

/// The viscous limit `0.125 h^2 / nu` (Morris et al. 1997, eq. 20) for the most
/// viscous material.
fn dt_limit(model: &Model) -> Option<(&'static str, Real)> {
    let c = model.consts::<FluidConsts>();
    let nu = c
        .viscosity
        .iter()
        .zip(model.materials.iter())
        .map(|(v, m)| v.effective_nu(m.rest_density))
        .fold(0.0, Real::max);
    let h = 0.5 * model.kernel.support();
    (nu > 0.0).then(|| ("viscosity", 0.125 * h * h / nu))
}

/// The fluid's kinetic energy `sum_i m_i |v_i|^2 / 2` (J): watching it fall tells
/// when a scene has settled.
fn measures(sim: &crate::Simulation) -> Vec<crate::simulation::Measure> {
    let several = sim.channels().iter().any(|c| c.name == "material");
    let p = sim.read(if several { &["velocity", "material"] } else { &["velocity"] });
    let Some(v) = p.channel("velocity").and_then(|v| v.as_vectors()) else { return Vec::new() };
    let materials = &sim.model().materials;
    let index = p.channel("material").and_then(|m| m.as_exact());
    let energy: f64 = v
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let m = materials.get(index.map_or(0, |m| usize::from(m[i]))).mass as f64;
            0.5 * m * f64::from(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        })
        .sum();
    vec![crate::simulation::Measure::new("fluid.kinetic_energy", energy, "J")]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attrs::Column;

    #[test]
    fn the_counted_particles_are_those_a_simulation_builds() {
        for spacing in ["0.05", "0.037", "0.02"] {
            let scene = crate::scene::load::from_preset("dam_break", &[format!("particle_spacing={spacing}")]).unwrap();
            let counted = count(&scene)[0].1;
            let built = crate::Simulation::new_cpu(scene).unwrap().particle_count() as u64;
            assert_eq!(counted, built, "spacing {spacing}");
        }
    }

    /// A sphere holds about pi/6 of its cube's lattice points and a cylinder pi/4,
    /// each within its shape; a mesh cannot also be given a shape.
    #[test]
    fn spheres_and_cylinders_hold_their_share_of_the_box() {
        let built = |shape: &str| {
            let o =
                [format!("fluids[0].blocks=[{{\"min\":[0.1,0.1,0.1],\"max\":[0.5,0.5,0.5],\"shape\":\"{shape}\"}}]")];
            let scene = crate::scene::load::from_preset("dam_break", &o).unwrap();
            let sim = crate::Simulation::new_cpu(scene).unwrap();
            let Column::Vec3(x) = &sim.backend().download(&["x"])[0] else { panic!("positions") };
            x.clone()
        };
        let cube = built("box").len() as f64;
        for (shape, share, axis) in
            [("sphere", std::f64::consts::PI / 6.0, None), ("cylinder_y", std::f64::consts::PI / 4.0, Some(1))]
        {
            let x = built(shape);
            let r = x.len() as f64 / cube;
            assert!((r - share).abs() < 0.03, "{shape}: {r} of the box's points, against {share}");
            for p in &x {
                let mut d = *p - Vec3::splat(0.3);
                if let Some(k) = axis {
                    d[k] = 0.0;
                }
                assert!(d.length() <= 0.2 + 1e-4, "{shape}: a particle at {p} outside");
            }
        }
        let o = [
            "fluids[0].blocks[0].shape=\"sphere\"".to_string(),
            "fluids[0].blocks[0].mesh={\"asset\":\"x.obj\"}".to_string(),
        ];
        let err = crate::scene::load::from_preset("dam_break", &o).map(|_| ()).unwrap_err().to_string();
        assert!(err.contains("fluids[0].blocks[0].shape"), "{err}");
    }

    /// A fluid without blocks that nothing fills is refused naming the field (it
    /// would be a scene of no particles); one that the snowfall's release or a
    /// melting fills is accepted, as the presets that start it empty.
    #[test]
    fn a_fluid_without_blocks_needs_something_that_fills_it() {
        let load = |preset: &str, o: &[&str]| {
            let o: Vec<String> = o.iter().map(|s| s.to_string()).collect();
            crate::scene::load::from_preset(preset, &o).map(|_| ()).map_err(|e| e.to_string())
        };
        let err = load("dam_break", &["fluids[0].blocks=[]"]).unwrap_err();
        assert!(err.starts_with("fluids[0].blocks: must hold at least one block"), "{err}");
        assert!(err.contains("snowfall.release.fluid or heat.fluids[*].melting.into"), "{err}");
        // The second fluid empty, the first not: the second is named.
        let second = r#"fluids=[{"blocks":[{"min":[0,0,0],"max":[0.5,1,0.25]}]},{"name":"oil","blocks":[]}]"#;
        let err = load("dam_break", &[second]).unwrap_err();
        assert!(err.starts_with("fluids[1].blocks: must hold at least one block"), "{err}");
        assert!(err.contains("\"oil\""), "{err}");
        // The snow the snowfall's cover releases, and water only the ice's melt becomes.
        assert_eq!(load("snowfall_then_avalanche", &[]), Ok(()));
        assert_eq!(load("ice_cube_in_glass", &["fluids[0].blocks=[]"]), Ok(()));
        // Without the release, or released into another fluid, the snow stays empty.
        let err = load("snowfall_then_avalanche", &[r#"snowfall.release=null"#]);
        assert!(err.as_ref().is_err_and(|e| e.contains("fluids[0].blocks")), "{err:?}");
        // Without the melting, the water stays empty.
        let err = load("ice_cube_in_glass", &["fluids[0].blocks=[]", "heat.fluids[1].melting=null"]);
        assert!(err.as_ref().is_err_and(|e| e.contains("fluids[0].blocks")), "{err:?}");
    }
}
