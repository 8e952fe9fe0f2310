//! The snow module: generalised Newtonian fluids (Cross, power law, Bingham,
//! Herschel-Bulkley, Carreau) for snow avalanches and other non-Newtonian flows.
//! The viscosity of each particle follows from its shear rate; the viscous force
//! is that of the stress `2 mu D` between each pair. docs/snow.md states the models with
//! their units and references.
//!
//! - [`spec`]: the scene section (`snow`).
//! - [`rheology`]: the viscosity laws.
//! - [`shear`]: the shear-rate pass, which writes the core's per-particle
//!   viscosity ([`crate::quantities::VISCOSITY`]); the core's
//!   [`viscosity`](crate::viscosity) adds its force, explicit or implicit.
//! - [`presets`]: channel flows and the avalanche.
//! - [`channel`]: reference profiles of the channel flows; [`cases`]: validation
//!   cases and the stability battery.

pub mod cases;
pub mod channel;
pub mod presets;
pub mod rheology;
pub mod shear;
pub mod spec;

use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use crate::channels::{ChannelSpec, Source};
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::module::{BenchCase, BenchKind, BenchSize, ModuleDef, Section};
use crate::quantities::{Claim, Write};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
use crate::scene::validate::Checker;
use crate::simulation::Measure;
use crate::viscosity::Integration;
use rheology::Law;
use spec::Rheology;

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "snow",
    about: "Non-Newtonian viscosity (Cross, power law, Bingham, Herschel-Bulkley, Carreau) for snow avalanches.",
    requires: &["fluid"],
    section: Some(Section {
        def: SectionDef::of::<spec::Snow>(SECTION),
        missing: Some("required by the module \"snow\" (each fluid's rheology)"),
    }),
    validate,
    count: |_| Vec::new(),
    materials: |_| 0,
    claims,
    particles: |_, _| Ok(()),
    build,
    retune,
    tunables: TUNABLES,
    cpu: &[("snow.shear", &shear::Shear)],
    presets: presets::PRESETS,
    dt_limit,
    measures,
    cases: cases::CASES,
    stability: cases::STABILITY,
    bench: &[BenchCase {
        name: "avalanche",
        about: "The avalanche preset: the time step against the explicit viscous limit, front and run-out",
        kind: BenchKind::Run {
            preset: "avalanche",
            measures: &["snow.explicit_dt_limit", "snow.front", "snow.runout"],
            size: BenchSize::Particles,
        },
    }],
};

/// The module's live settings.
pub const TUNABLES: &[Tunable] = &[
    Tunable {
        path: "snow.fluids[*]",
        unit: "",
        min: None,
        max: None,
        about: "A fluid's rheology, e.g. {\"model\": \"cross\", \"mu_0\": Pa s, \"mu_inf\": Pa s, \"k\": s, \"n\": 1}.",
        module: "snow",
    },
    Tunable {
        path: "snow.walls",
        unit: "",
        min: None,
        max: None,
        about: "Walls' viscous condition: \"no_slip\" or \"slip\" (the terrain's Coulomb friction alone holds the base).",
        module: "snow",
    },
    Tunable {
        path: "snow.max_viscosity",
        unit: "Pa s",
        min: Some(0.0),
        max: Some(1e9),
        about: "The viscosity clamp (it also sets the viscous time-step limit).",
        module: "snow",
    },
];

/// The shear rate `sqrt(2 D:D)` (1/s) of the last evaluation.
pub static SHEAR_RATE: AttrSpec = AttrSpec {
    name: "shear_rate",
    elem: Elem::F32,
    unit: "1/s",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "snow",
    about: "Shear rate sqrt(2 D:D) of the last evaluation.",
};

/// The shear-rate channel.
pub const SHEAR_RATE_CHANNEL: ChannelSpec = ChannelSpec {
    name: "shear_rate",
    unit: "1/s",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "snow",
    about: "Shear rate sqrt(2 D:D).",
    source: Source::Attr("shear_rate"),
};

/// The module's constants.
#[derive(Debug, Clone)]
pub struct SnowConsts {
    /// The law of each material.
    pub laws: Vec<Law>,
}

impl SnowConsts {
    fn new(snow: &spec::Snow, materials: &[crate::materials::Material]) -> Self {
        let own: Vec<Law> = snow.fluids.iter().map(|r| Law::new(r, snow.max_viscosity)).collect();
        Self { laws: crate::materials::per_material(materials, &own) }
    }

    /// Whether material `m` has a rheology (is snow, for the measures).
    pub fn is_snow(&self, m: usize) -> bool {
        self.laws[m].kind != rheology::Kind::None
    }
}

/// The module's section of a scene.
pub const SECTION: &str = "snow";

/// The scene's `snow` section (the registry builds the module only for scenes with one).
pub fn section(scene: &Scene) -> spec::Snow {
    scene.section(SECTION).expect("the registry builds snow only for scenes with a snow section")
}

fn validate(scene: &Scene, c: &mut Checker) {
    let Some(snow) = scene.section::<spec::Snow>(SECTION) else { return };
    let fluids = crate::module::materials(scene);
    if snow.fluids.len() != fluids {
        c.fail("snow.fluids", format!("must hold one entry per fluid ({fluids}), got {}", snow.fluids.len()));
    }
    c.positive("snow.max_viscosity", snow.max_viscosity);
    crate::viscosity::validate_solver(c, "snow.solver", snow.solver);
    for (i, r) in snow.fluids.iter().enumerate() {
        let p = |f: &str| format!("snow.fluids[{i}].{f}");
        match *r {
            Rheology::None => {}
            Rheology::Newtonian { mu } => c.non_negative(&p("mu"), mu),
            Rheology::Cross { mu_0, mu_inf, k, n } | Rheology::Carreau { mu_0, mu_inf, lambda: k, n } => {
                c.non_negative(&p("mu_0"), mu_0);
                c.non_negative(&p("mu_inf"), mu_inf);
                let time = if matches!(r, Rheology::Cross { .. }) { "k" } else { "lambda" };
                c.non_negative(&p(time), k);
                c.within(&p("n"), n, 0.0, 10.0);
            }
            Rheology::PowerLaw { k, n } => {
                c.non_negative(&p("k"), k);
                c.within(&p("n"), n, 0.05, 10.0);
            }
            Rheology::Bingham { yield_stress, mu_p, m } => {
                c.non_negative(&p("yield_stress"), yield_stress);
                c.non_negative(&p("mu_p"), mu_p);
                c.positive(&p("m"), m);
            }
            Rheology::HerschelBulkley { yield_stress, k, n, m } => {
                c.non_negative(&p("yield_stress"), yield_stress);
                c.non_negative(&p("k"), k);
                c.within(&p("n"), n, 0.05, 10.0);
                c.positive(&p("m"), m);
            }
        }
    }
}

/// Each fluid's rheology sets its viscosity (a module's law may scale it, except
/// a fluid's without a rheology, whose viscosity is 0).
fn claims(scene: &Scene) -> Vec<Claim> {
    let snow = section(scene);
    let how = Integration { solver: snow.solver, walls: snow.walls };
    let rheology = |(i, r): (usize, &Rheology)| {
        let none = *r == Rheology::None;
        Claim {
            material: i,
            path: if none { format!("{SECTION}.fluids[{i}].model") } else { format!("{SECTION}.fluids[{i}]") },
            write: Write::Sets { how, scalable: !none },
            fix: r#"must not be "none" (a Newtonian fluid: {"model": "newtonian", "mu": its viscosity})"#,
        }
    };
    snow.fluids.iter().enumerate().map(rheology).collect()
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let snow = section(scene);
    b.zeros(&SHEAR_RATE);
    // Another module's law may scale the rheology (the core allocates the factor).
    b.pass(if b.quantities.scaled() { &shear::SHEAR_SHIFTED } else { &shear::SHEAR });
    b.channel(SHEAR_RATE_CHANNEL);
    let consts = SnowConsts::new(&snow, b.materials());
    b.set_consts(Front::new(b, &consts));
    b.set_consts(consts);
    Ok(())
}

fn retune(scene: &Scene, model: &mut Model) {
    model.set_consts(SnowConsts::new(&section(scene), model.materials.as_slice()));
}

/// The explicit viscous limit `0.125 h^2 rho0 / mu_max` (Morris et al. 1997, eq. 20)
/// at each material's clamp, if any material has a viscosity.
pub fn explicit_dt_limit(model: &Model) -> Option<Real> {
    let c = model.consts::<SnowConsts>();
    let nu = c.laws.iter().zip(model.materials.iter()).map(|(l, m)| l.max / m.rest_density).fold(0.0, Real::max);
    let h = 0.5 * model.kernel.support();
    (nu > 0.0).then(|| 0.125 * h * h / nu)
}

/// The explicit viscous limit, unless the viscosity is implicit (no limit on dt).
fn dt_limit(model: &Model) -> Option<(&'static str, Real)> {
    let limit = explicit_dt_limit(model).filter(|_| !crate::viscosity::is_implicit(model))?;
    Some(("non-Newtonian viscosity", limit))
}

/// Where the snow's front started: its largest x (m) at build.
#[derive(Debug, Clone, Copy)]
pub struct Front {
    /// x of the foremost snow particle at the start (m).
    pub start: Real,
}

impl Front {
    fn new(b: &ModelBuilder, c: &SnowConsts) -> Self {
        let Some(Column::Vec3(x)) = b.column("x") else { panic!("the core allocates positions first") };
        let material = match b.column("material") {
            Some(Column::U32(m)) => Some(m),
            _ => None,
        };
        let start = x
            .iter()
            .enumerate()
            .filter(|(i, _)| c.is_snow(material.map_or(0, |m| m[*i] as usize)))
            .map(|(_, p)| p.x)
            .fold(Real::NEG_INFINITY, Real::max);
        Front { start }
    }
}

/// The snow's front (its largest x, m; avalanches run along +x), its run-out (how
/// far the front has moved from where it started, m), the largest viscosity (Pa s)
/// and the explicit viscous limit on dt (s; what an implicit solve lifts).
fn measures(sim: &crate::Simulation) -> Vec<Measure> {
    let mut m = front_and_viscosity(sim);
    if let Some(limit) = explicit_dt_limit(sim.model()) {
        m.push(Measure::new("snow.explicit_dt_limit", f64::from(limit), "s"));
    }
    m
}

fn front_and_viscosity(sim: &crate::Simulation) -> Vec<Measure> {
    let several = sim.channels().iter().any(|c| c.name == "material");
    let p = sim.read(if several { &["viscosity", "material"] } else { &["viscosity"] });
    let Some(mu) = p.channel("viscosity").and_then(|t| t.as_scalars()) else { return Vec::new() };
    let material = p.channel("material").and_then(|m| m.as_exact());
    let (c, start) = (sim.model().consts::<SnowConsts>(), sim.model().consts::<Front>().start);
    let mut front = f64::NEG_INFINITY;
    for (i, x) in p.positions.iter().enumerate() {
        if c.is_snow(material.map_or(0, |m| usize::from(m[i]))) {
            front = front.max(f64::from(x[0]));
        }
    }
    let max_mu = mu.iter().fold(0.0f64, |m, &v| m.max(f64::from(v)));
    if !front.is_finite() {
        return vec![Measure::new("snow.max_viscosity", max_mu, "Pa s")];
    }
    vec![
        Measure::new("snow.front", front, "m"),
        Measure::new("snow.runout", front - f64::from(start), "m"),
        Measure::new("snow.max_viscosity", max_mu, "Pa s"),
    ]
}
