//! The heat module: a temperature per particle, conduction between particles of
//! one fluid or of several, walls held at a temperature or insulated, volumetric
//! heat sources and heat fluxes through walls, and the Boussinesq buoyancy and the
//! temperature-dependent viscosity that couple temperature back to the flow. docs/heat.md states the model with its
//! units and references.
//!
//! - [`spec`]: the scene section (`heat`).
//! - [`conduction`]: the conduction pass (Cleary & Monaghan 1999).
//! - [`passes`]: buoyancy (a force pass accumulating into `a`) and the
//!   integration `T += dt dT/dt` in the kick stage.
//! - [`phase`]: melting and freezing by enthalpy, with latent heat: a fluid that
//!   melts (`melting`) and its melt, a phase of it, and the liquid fraction.
//! - [`viscosity`]: temperature-dependent viscosity laws, written into the core's
//!   per-particle viscosity, or into its factor where another module sets it
//!   ([`crate::quantities`]).
//! - [`presets`]: `conduction`, `convection`, `two_fluids`, `heated_cavity`,
//!   `heated_channel`, `layers`.
//! - [`cases`]: validation cases and the stability battery.
//! - `validate`: the section's checks, each naming the setting it rejects.

pub mod cases;
pub mod conduction;
pub mod passes;
pub mod phase;
pub mod presets;
pub mod spec;
pub mod stefan;
mod validate;
pub mod viscosity;

use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use crate::channels::{ChannelSpec, Source};
use crate::guard::Bound;
use crate::kernel::Kernel;
use crate::materials::{Material, per_material};
use crate::math::{Aabb, Real, Vec3};
use crate::model::{BuildError, Model, ModelBuilder};
use crate::module::{BenchCase, BenchKind, ModuleDef, Section};
use crate::quantities::{Claim, Role as QuantityRole, Write};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
use crate::simulation::Measure;
use crate::viscosity::{Integration, WallShear};
use viscosity::TemperatureLaw;

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "heat",
    about: "Temperature: conduction between fluids and with walls, heat sources, Boussinesq buoyancy.",
    requires: &["fluid"],
    section: Some(Section {
        def: SectionDef::of::<spec::Heat>(SECTION),
        missing: Some("required by the module \"heat\" (each fluid's thermal properties)"),
    }),
    validate: validate::validate,
    count: |_| Vec::new(),
    materials: |_| 0,
    claims,
    particles: phase::declare,
    build,
    retune,
    tunables: TUNABLES,
    cpu: &[
        ("heat.conduction", &conduction::Conduction),
        ("heat.buoyancy", &passes::Buoyancy),
        ("heat.integrate", &passes::Integrate),
        ("heat.melt", &phase::Melt),
        ("heat.input", &phase::Input),
        ("heat.viscosity", &viscosity::Viscosity),
        ("heat.viscosity_shift", &viscosity::Shift),
    ],
    presets: presets::PRESETS,
    dt_limit,
    measures,
    cases: cases::CASES,
    stability: cases::STABILITY,
    bench: &[BenchCase {
        name: "heat",
        about: "The dam break with heat (water's properties, a tenfold expansion, a floor held at 350 K under \
                water at 300 K) beside the dam break alone",
        kind: BenchKind::Beside(&[
            "modules=[\"fluid\",\"heat\"]",
            "heat={\"fluids\":[{\"conductivity\":0.6,\"heat_capacity\":4186,\"expansion\":2e-3,\"temperature\":300}],\
             \"walls\":[{\"min\":[-1,-1,-1],\"max\":[3,0,1],\"temperature\":350}]}",
        ]),
    }],
};

/// The module's live settings.
pub const TUNABLES: &[Tunable] = &[
    Tunable {
        path: "heat.fluids[*].conductivity",
        unit: "W/(m K)",
        min: Some(0.0),
        max: Some(1e6),
        about: "A fluid's thermal conductivity.",
        module: "heat",
    },
    Tunable {
        path: "heat.fluids[*].expansion",
        unit: "1/K",
        min: Some(0.0),
        max: Some(0.1),
        about: "A fluid's thermal expansion coefficient (Boussinesq buoyancy).",
        module: "heat",
    },
];

/// Temperature (K), the module's state.
pub static TEMPERATURE: AttrSpec = AttrSpec {
    name: "temperature",
    elem: Elem::F32,
    unit: "K",
    role: Role::State,
    added_later: false,
    space: PARTICLES,
    module: "heat",
    about: "Absolute temperature.",
};

/// The part of the temperature increments that f32 rounding dropped, carried into
/// the next step (compensated summation, Kahan 1965): a particle of water near 300 K
/// takes increments of a few 1e-6 K per step under a gentle flux, under half the f32
/// spacing there (3e-5 K), which plain `T += dt dT/dt` would lose entirely.
pub static TEMPERATURE_CARRY: AttrSpec = AttrSpec {
    name: "temperature_carry",
    elem: Elem::F32,
    unit: "K",
    role: Role::State,
    added_later: true,
    space: PARTICLES,
    module: "heat",
    about: "Rounding lost from the temperature's last increments, subtracted from the next.",
};

/// dT/dt of the last evaluation (K/s): conduction and sources.
pub static HEAT_RATE: AttrSpec = AttrSpec {
    name: "heat_rate",
    elem: Elem::F32,
    unit: "K/s",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "heat",
    about: "Rate of change of temperature from conduction and sources.",
};

/// The temperature channel (a row of proto/channels.json).
pub const TEMPERATURE_CHANNEL: ChannelSpec = ChannelSpec {
    name: "temperature",
    unit: "K",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "heat",
    about: "Temperature.",
    source: Source::Attr("temperature"),
};

/// Each particle's liquid fraction, in scenes where a fluid melts.
pub const LIQUID_FRACTION_CHANNEL: ChannelSpec = ChannelSpec {
    name: "liquid_fraction",
    unit: "1",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "heat",
    about: "Liquid fraction beta of a particle that melts or freezes: 0 solid, 1 liquid, in between while melting or freezing (0 for materials that never change phase).",
    source: Source::Attr("liquid_fraction"),
};

/// Most wall boxes, and most heat sources and fluxes together, a scene may declare
/// (the GPU uniform's arrays).
pub const MAX_BOXES: usize = 8;

/// The module's constants.
#[derive(Debug, Clone)]
pub struct HeatConsts {
    /// Conductivity k of each material (W/(m K)).
    pub conductivity: Vec<Real>,
    /// Specific heat capacity c of each material (J/(kg K)).
    pub capacity: Vec<Real>,
    /// Thermal expansion beta of each material (1/K).
    pub expansion: Vec<Real>,
    /// `4 k_a k_b / (k_a + k_b)` (twice the harmonic mean) at `a * materials + b`,
    /// times the lattice normalisation [`Kernel::pair_lattice_scale`].
    pub pair_conductivity: Vec<Real>,
    /// Boussinesq reference temperature T0 (K).
    pub reference: Real,
    /// The acceleration buoyancy acts along (m/s^2).
    pub gravity: Vec3,
    /// Walls held at a temperature: box and temperature (K).
    pub walls: Vec<(Aabb, Real)>,
    /// Volumetric heat sources and the layers wall fluxes enter through.
    pub sources: Vec<HeatInput>,
    /// The temperature law of each material's viscosity (kind `None` where it has none).
    pub viscosity: Vec<TemperatureLaw>,
    /// Whether the laws scale the viscosity another module sets (the core's
    /// `viscosity_shift`) rather than set it (`mu`).
    pub shifts_rheology: bool,
    /// The temperatures the scene may reach, `heat.range` (K).
    pub range: [Real; 2],
    /// Each material's phase change, where it melts or freezes.
    pub phases: Vec<Option<phase::PhaseChange>>,
}

/// Where heat enters the fluid, and how much.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatInput {
    /// A source's box, or the box a wall flux crosses the surface of.
    pub region: Aabb,
    /// 0 for a volumetric source (the particles inside `region`); for a wall flux
    /// the thickness (m, one particle spacing) of the layer outside `region` it
    /// enters through.
    pub layer: Real,
    /// A source's power density (W/m^3), or the power (W) a flux gives each particle
    /// of its layer: the flux times `d^2`.
    pub power: Real,
}

impl HeatInput {
    /// Whether the particle at `x` takes this source's power (the GPU's
    /// `conduction.wgsl` tests the same).
    pub fn contains(&self, x: Vec3) -> bool {
        let inside = self.region.contains(x);
        if self.layer > 0.0 { !inside && self.region.expanded(self.layer).contains(x) } else { inside }
    }
}

impl HeatConsts {
    /// The constants of `scene`'s heat section, one per material of `materials` (a
    /// phase takes the entry of the material it is like).
    fn new(scene: &Scene, materials: &[Material], kernel: &Kernel, role: Option<QuantityRole>) -> Self {
        let heat = section(scene);
        let spacing = scene.particle_spacing;
        let each = |f: fn(&spec::ThermalFluid) -> Real| {
            per_material(materials, &heat.fluids.iter().map(f).collect::<Vec<_>>())
        };
        let conductivity = each(|f| f.conductivity);
        let capacity = each(|f| f.heat_capacity);
        let n = conductivity.len();
        let scale = kernel.pair_lattice_scale(spacing);
        let mut pair_conductivity = Vec::with_capacity(n * n);
        for &a in &conductivity {
            for &b in &conductivity {
                pair_conductivity.push(if a + b > 0.0 { scale * 4.0 * a * b / (a + b) } else { 0.0 });
            }
        }
        let aabb = |min: [f32; 3], max: [f32; 3]| Aabb::new(min.into(), max.into());
        Self {
            conductivity,
            phases: phase::phases(&heat, materials, &capacity),
            capacity,
            expansion: each(|f| f.expansion),
            pair_conductivity,
            reference: heat.reference_temperature,
            gravity: heat.buoyancy_gravity.unwrap_or(scene.gravity).into(),
            walls: heat.walls.iter().map(|w| (aabb(w.min, w.max), w.temperature)).collect(),
            sources: heat
                .sources
                .iter()
                .map(|s| HeatInput { region: aabb(s.min, s.max), layer: 0.0, power: s.power })
                .chain(heat.fluxes.iter().map(|f| HeatInput {
                    region: aabb(f.min, f.max),
                    layer: spacing,
                    power: f.flux * spacing * spacing,
                }))
                .collect(),
            viscosity: per_material(
                materials,
                &heat
                    .fluids
                    .iter()
                    .map(|f| TemperatureLaw::new(f.viscosity.as_ref(), heat.max_viscosity, heat.reference_temperature))
                    .collect::<Vec<_>>(),
            ),
            shifts_rheology: role == Some(QuantityRole::Scales),
            range: heat.range,
        }
    }

    /// The temperature of the wall particle at `x`, or `None` where it is insulated.
    pub fn wall_temperature(&self, x: Vec3) -> Option<Real> {
        self.walls.iter().find(|(b, _)| b.contains(x)).map(|&(_, t)| t)
    }

    /// The power density (W/m^3) the sources and wall fluxes give the particle at `x`
    /// of density `rho` and mass `mass`. A particle in a flux's layer takes the flux
    /// times `d^2`, the wall area it covers on the particle lattice, whatever its
    /// volume `mass / rho`: the layer against a face of area A, `A / d^2` particles,
    /// then takes the flux times A.
    pub fn source(&self, x: Vec3, rho: Real, mass: Real) -> Real {
        let power = |s: &HeatInput| if s.layer > 0.0 { s.power * rho / mass } else { s.power };
        self.sources.iter().filter(|s| s.contains(x)).map(power).sum()
    }

    /// Whether any material's viscosity follows its temperature.
    pub fn viscous(&self) -> bool {
        self.viscosity.iter().any(|l| l.kind != viscosity::Kind::None)
    }

    /// Whether any material melts or freezes.
    pub fn melts(&self) -> bool {
        self.phases.iter().any(Option::is_some)
    }

    /// Whether the heat walls and sources give is summed apart (`heat_in`): where a
    /// fluid melts and there are walls held at a temperature or sources.
    pub fn takes_input(&self) -> bool {
        self.melts() && !(self.walls.is_empty() && self.sources.is_empty())
    }

    /// Whether any material feels buoyancy.
    pub fn buoyant(&self) -> bool {
        self.expansion.iter().any(|&b| b != 0.0)
    }
}

/// The module's section of a scene.
pub const SECTION: &str = "heat";

/// The scene's `heat` section (the registry builds the module only for scenes with one).
pub fn section(scene: &Scene) -> spec::Heat {
    scene.section(SECTION).expect("the registry builds heat only for scenes with a heat section")
}

/// Each particle starts at its fluid's temperature, or its region's.
fn initial_temperatures(heat: &spec::Heat, b: &ModelBuilder) -> Vec<Real> {
    let Some(Column::Vec3(x)) = b.column("x") else { panic!("the core allocates positions first") };
    let material = match b.column("material") {
        Some(Column::U32(m)) => Some(m),
        _ => None,
    };
    x.iter()
        .enumerate()
        .map(|(i, &p)| {
            let own = heat.fluids[b.materials()[material.map_or(0, |m| m[i] as usize)].settings].temperature;
            let region = heat.regions.iter().rev().find(|r| Aabb::new(r.min.into(), r.max.into()).contains(p));
            region.map_or(own, |r| r.temperature)
        })
        .collect()
}

/// Each fluid's temperature law sets its viscosity, or scales the viscosity
/// another module sets from the fluid's state (a rheology) by `mu(T) / mu(T0)`.
fn claims(scene: &Scene) -> Vec<Claim> {
    let heat = section(scene);
    let how = Integration { solver: heat.viscous_solver, walls: WallShear::NoSlip };
    let law = |(i, f): (usize, &spec::ThermalFluid)| {
        f.viscosity.is_some().then(|| Claim {
            material: i,
            path: format!("{SECTION}.fluids[{i}].viscosity"),
            write: Write::SetsOrScales { how },
            fix: "",
        })
    };
    heat.fluids.iter().enumerate().filter_map(law).collect()
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let heat = section(scene);
    let t = initial_temperatures(&heat, b);
    b.attr(&TEMPERATURE, Column::F32(t.clone()));
    b.zeros(&TEMPERATURE_CARRY);
    b.zeros(&HEAT_RATE);
    let consts = HeatConsts::new(scene, b.materials(), &b.kernel, b.quantities.role(MODULE.id));
    b.pass(if consts.takes_input() { &conduction::CONDUCTION_INPUT } else { &conduction::CONDUCTION });
    if consts.buoyant() {
        b.pass(&passes::BUOYANCY);
    }
    if consts.melts() {
        phase::build(b, &consts, &t);
    } else {
        b.pass(&passes::INTEGRATE);
    }
    if consts.viscous() {
        b.pass(if consts.shifts_rheology { &viscosity::SHIFT } else { &viscosity::VISCOSITY });
    }
    b.bound(Bound { attr: "temperature", what: "temperature", unit: "K", min: heat.range[0], max: heat.range[1] });
    b.channel(TEMPERATURE_CHANNEL);
    b.set_consts(consts);
    Ok(())
}

/// Conductivities and expansion may change; buoyancy's pass comes and goes with it.
fn retune(scene: &Scene, model: &mut Model) {
    let consts = HeatConsts::new(scene, model.materials.as_slice(), &model.kernel, model.quantities.role(MODULE.id));
    let names: Vec<&str> = model.plan.passes().iter().map(|p| p.name).collect();
    if consts.buoyant() != names.contains(&passes::BUOYANCY.name) {
        let mut list: Vec<_> =
            model.plan.passes().iter().copied().filter(|p| p.name != passes::BUOYANCY.name).collect();
        if consts.buoyant() {
            list.push(&passes::BUOYANCY);
        }
        let attrs: Vec<&str> = model.layout.specs().map(|s| s.name).collect();
        model.plan = crate::plan::Plan::build(list, &attrs).expect("buoyancy keeps the plan valid");
    }
    model.set_consts(consts);
}

/// The explicit diffusion limit `dt <= 0.1 rho c h^2 / k` (Cleary & Monaghan 1999,
/// section 5) for the most diffusive material, and, where the temperature laws'
/// viscosity is explicit, the viscous limit `0.125 h^2 rho0 / mu` (Morris et al.
/// 1997, eq. 20) at the largest viscosity a law gives within `heat.range`: the
/// smaller of the two.
fn dt_limit(model: &Model) -> Option<(&'static str, Real)> {
    let c = model.consts::<HeatConsts>();
    let alpha = c
        .conductivity
        .iter()
        .zip(&c.capacity)
        .zip(model.materials.iter())
        .map(|((&k, &cp), m)| k / (m.rest_density * cp))
        .fold(0.0, Real::max);
    let h = 0.5 * model.kernel.support();
    let diffusion = (alpha > 0.0).then(|| ("heat conduction", 0.1 * h * h / alpha));
    let [lo, hi] = c.range;
    let nu = c
        .viscosity
        .iter()
        .zip(model.materials.iter())
        .map(|(l, m)| l.largest(lo, hi) / m.rest_density)
        .fold(0.0, Real::max);
    // Scaling a rheology, the snow module's clamp bounds the viscosity and its limit.
    let explicit = c.viscous() && !c.shifts_rheology && !crate::viscosity::is_implicit(model) && nu > 0.0;
    let viscous = explicit.then(|| ("temperature-dependent viscosity", 0.125 * h * h / nu));
    [diffusion, viscous].into_iter().flatten().min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Mean, smallest and largest temperature (K) and the heat content (J, summed in
/// f64): `sum_i m_i c_i T_i`, where a fluid melts `sum_i m_i (c_s T_m + H_i)` for
/// its particles (the enthalpy from T and the liquid fraction, [`phase`]); there
/// also the mass of solid and of melt (kg) and the latent heat stored (J).
fn measures(sim: &crate::Simulation) -> Vec<Measure> {
    let (model, c) = (sim.model(), sim.model().consts::<HeatConsts>());
    let several = sim.channels().iter().any(|c| c.name == "material");
    let names: &[&str] = match (c.melts(), several) {
        (true, _) => &["temperature", "material", "liquid_fraction"],
        (false, true) => &["temperature", "material"],
        (false, false) => &["temperature"],
    };
    let p = sim.read(names);
    let Some(t) = p.channel("temperature").and_then(|t| t.as_scalars()) else { return Vec::new() };
    let material = p.channel("material").and_then(|m| m.as_exact());
    let beta = p.channel("liquid_fraction").and_then(|b| b.as_scalars());
    let (mut sum, mut heat, mut lo, mut hi) = (0.0f64, 0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    let (mut solid, mut melt, mut latent) = (0.0f64, 0.0f64, 0.0f64);
    for (i, &t) in t.iter().enumerate() {
        let m = material.map_or(0, |m| usize::from(m[i]));
        let mass = f64::from(model.materials.get(m).mass);
        match (c.phases[m], beta) {
            (Some(p), Some(beta)) => {
                let b = beta[i];
                heat += mass * p.heat(p.enthalpy(t, b));
                (solid, melt) = (solid + mass * f64::from(1.0 - b), melt + mass * f64::from(b));
                latent += mass * f64::from(b) * f64::from(p.latent);
            }
            _ => heat += mass * f64::from(c.capacity[m]) * f64::from(t),
        }
        let t = f64::from(t);
        sum += t;
        (lo, hi) = (lo.min(t), hi.max(t));
    }
    let mean = sum / t.len().max(1) as f64;
    let mut out = vec![
        Measure::new("heat.mean_temperature", mean, "K"),
        Measure::new("heat.min_temperature", lo, "K"),
        Measure::new("heat.max_temperature", hi, "K"),
        Measure::new("heat.total_heat", heat, "J"),
    ];
    if model.layout.spec(phase::HEAT_IN.name).is_some() {
        let cols = sim.backend().download(&[phase::HEAT_IN.name, "material"]);
        if let [Column::F32(q), Column::U32(m)] = &cols[..] {
            let mass = |m: u32| f64::from(model.materials.get(m as usize).mass);
            out.push(Measure::new("heat.heat_in", q.iter().zip(m).map(|(&q, &m)| mass(m) * f64::from(q)).sum(), "J"));
        }
    }
    if c.melts() {
        out.push(Measure::new("heat.solid_mass", solid, "kg"));
        out.push(Measure::new("heat.melt_mass", melt, "kg"));
        out.push(Measure::new("heat.latent_heat", latent, "J"));
    }
    out
}
