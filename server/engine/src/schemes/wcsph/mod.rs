//! Weakly compressible SPH (Monaghan 1994, J. Comput. Phys. 110; Becker & Teschner
//! 2007, "Weakly compressible SPH for free surface flows", SCA): pressure from an
//! equation of state of the summation density, explicit steps limited by the speed
//! of sound.
//!
//! A step: sort, density, pre-force (`wcsph.eos`, `wcsph.wall_pressure`), force
//! (the fluid module's pass with the pressure term fused in), measure, then the
//! integrator:
//! - symplectic Euler: evaluate `a(x)`, then `v += dt a`, `x += dt v`;
//! - leap-frog kick-drift-kick (Verlet 1967; Monaghan 2005, Rep. Prog. Phys. 68,
//!   section 6): `v += dt/2 a`, `x += dt v`, evaluate, `v += dt/2 a`, reusing the
//!   previous step's measures to choose dt.
//!
//! The modules' velocity solves (implicit viscosity, over the whole dt) and then the
//! kick-stage passes (XSPH) follow the kick after an evaluation; damping
//! multiplies velocities by `exp(-rate dt)` until its end time.
//!
//! With `solver.delta_sph`, the drift stage integrates the density
//! ([`continuity`]); the density stage then only finds neighbours.
//!
//! With `solver.transport_velocity`, the force stage also computes the background
//! pressure's push ([`transport`]), which the drift adds to the velocity it moves
//! particles with.

pub mod continuity;
pub mod cpu;
pub mod eos;
pub mod spec;
pub mod transport;

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role, WALLS};
use crate::channels::{ChannelSpec, Source};
use crate::clock::Clock;
use crate::guard::Halted;
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::plan::{PassSpec, Stage};
use crate::position_solve;
use crate::scene::sections::SectionDef;
use crate::scene::{Integrator, Scene};
use crate::scheme::{SchemeDef, Stages, StepReport, velocity_solves};
use eos::Eos;

/// The scheme's definition.
pub static SCHEME: SchemeDef = SchemeDef {
    id: "wcsph",
    about: "Weakly compressible SPH: equation of state, explicit steps at the speed of sound.",
    settings: &[
        SectionDef::of::<spec::DeltaSph>(DELTA_SPH),
        SectionDef::of::<spec::TransportVelocity>(TRANSPORT_VELOCITY),
    ],
    pressure_terms: true,
    validate,
    build,
    retune: |_, _| {},
    cpu: &[
        ("wcsph.eos", &cpu::EosPass),
        ("wcsph.wall_pressure", &cpu::WallPressure),
        ("wcsph.transport", &transport::Transport),
        ("wcsph.continuity", &continuity::Continuity),
        ("wcsph.integrate_density", &continuity::Integrate),
    ],
    step,
    signal_speed: |model| model.consts::<WcsphConsts>().signal_speed,
    position_solves: position_solve::When::AfterDrift,
};

/// δ-SPH's settings in `solver` ([`spec::DeltaSph`]; absent or `null`: the density is summed).
pub const DELTA_SPH: &str = "delta_sph";
/// The transport velocity's settings in `solver` ([`spec::TransportVelocity`]; absent or `null`: none).
pub const TRANSPORT_VELOCITY: &str = "transport_velocity";

/// `p / rho^2` of each particle (m^5/(kg s^2)), the pressure force's term.
pub static PTERM: AttrSpec = AttrSpec {
    name: crate::scheme::PRESSURE_TERM,
    elem: Elem::F32,
    unit: "m^5/(kg s^2)",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "wcsph",
    about: "Pressure over density squared.",
};

/// Pressure of each wall particle (Pa), extrapolated from the fluid.
pub static WALL_P: AttrSpec = AttrSpec {
    name: "wall_p",
    elem: Elem::F32,
    unit: "Pa",
    role: Role::Derived,
    added_later: false,
    space: WALLS,
    module: "wcsph",
    about: "Wall particle pressure (Adami et al. 2012).",
};

/// Pressure from density.
pub static EOS: PassSpec = PassSpec {
    name: "wcsph.eos",
    module: "wcsph",
    stage: Stage::PreForce,
    reads: &["rho"],
    writes: &["pterm"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// Wall pressures.
pub static WALL_PRESSURE: PassSpec = PassSpec {
    name: "wcsph.wall_pressure",
    module: "wcsph",
    stage: Stage::PreForce,
    reads: &["x", "rho", "pterm"],
    writes: &["wall_p"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The scheme's constants: each material's equation of state, and the
/// transport velocity's background pressure.
#[derive(Debug, Clone)]
pub struct WcsphConsts {
    /// Equation of state of each material.
    pub eos: Vec<Eos>,
    /// Background pressure (Pa) of the transport velocity, when the scene has one.
    pub transport: Option<Real>,
    /// δ-SPH's constants, when the scene integrates its density.
    pub delta: Option<continuity::DeltaConsts>,
    /// The CFL condition's signal speed (m/s): the fastest `sqrt(K_a / rho0_b)` of
    /// a fluid's bulk modulus `K_a = rho0_a c_a^2` and any fluid's rest density
    /// ([`signal_speed`]); the solver's speed of sound for one fluid.
    pub signal_speed: Real,
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let c = b.sound_speed()?;
    let eos: Vec<Eos> = b.materials().iter().map(|m| Eos::new(m.eos, m.rest_density, c)).collect();
    let transport = transport_velocity(scene).map(|t| t.background);
    let delta = delta_sph(scene).map(|d| continuity::build(b, d.delta, c, &eos));
    let signal_speed = signal_speed(b.materials(), c);
    b.set_consts(WcsphConsts { eos, transport, delta, signal_speed });
    b.zeros(&PTERM);
    b.zeros(&WALL_P);
    b.pass(&EOS);
    b.pass(&WALL_PRESSURE);
    if transport.is_some() {
        b.zeros(&crate::model::core_attrs::A_TRANSPORT);
        b.pass(&transport::TRANSPORT);
    }
    b.channel(PRESSURE_CHANNEL);
    Ok(())
}

/// The CFL condition's signal speed (m/s) of a scene whose speed of sound is `c`.
///
/// A particle of rest density `rho0_b` beside particles of a fluid with bulk
/// modulus `K_a = rho0_a c_a^2` feels their pressure respond to its motion with
/// `K_a`'s stiffness while its own inertia is `rho0_b`'s: the pair's mode
/// travels at `sqrt(K_a / rho0_b) = c_a sqrt(rho0_a / rho0_b)`, faster than
/// either fluid's sound where a light fluid touches a heavy one (`sqrt(10) c` at
/// a density ratio of 10). A step sized by `c` alone lets that mode grow at the
/// interface: the `layers` preset's speeds grew tenfold a second once its
/// damping stopped (docs/heat.md). `c_a` is the fluid's own speed
/// ([`crate::materials::EquationOfState::sound_speed`]): one fluid gets exactly `c`.
fn signal_speed(materials: &[crate::materials::Material], c: Real) -> Real {
    let lightest = materials.iter().map(|m| m.rest_density).fold(Real::INFINITY, Real::min);
    let felt = |m: &crate::materials::Material| m.eos.sound_speed(c) * (m.rest_density / lightest).sqrt();
    materials.iter().map(felt).fold(c, Real::max)
}

/// Checks the settings: the background pressure and δ, WCSPH's only.
fn validate(scene: &Scene, chosen: bool, c: &mut crate::scene::validate::Checker) {
    let only = |c: &mut crate::scene::validate::Checker, key: &str| {
        if !chosen {
            c.fail(&format!("solver.{key}"), "works with solver.method = \"wcsph\" only".into());
        }
    };
    if let Some(t) = transport_velocity(scene) {
        c.positive("solver.transport_velocity.background", t.background);
        only(c, TRANSPORT_VELOCITY);
    }
    if let Some(d) = delta_sph(scene) {
        c.within("solver.delta_sph.delta", d.delta, 0.0, 1.0);
        only(c, DELTA_SPH);
    }
    // The other schemes' steps are their own (DFSPH's: its solves between a kick and
    // a drift); leap-frog there would be silently ignored.
    if scene.solver.integrator == crate::scene::Integrator::Leapfrog {
        only(c, "integrator");
    }
}

/// The scene's δ-SPH settings, if its density is integrated.
pub fn delta_sph(scene: &Scene) -> Option<spec::DeltaSph> {
    scene.solver.settings(DELTA_SPH)
}

/// The scene's transport-velocity settings, if it has them.
pub fn transport_velocity(scene: &Scene) -> Option<spec::TransportVelocity> {
    scene.solver.settings(TRANSPORT_VELOCITY)
}

/// Pressure from density through each material's equation of state (WCSPH).
pub const PRESSURE_CHANNEL: ChannelSpec = ChannelSpec {
    name: "pressure",
    unit: "Pa",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "wcsph",
    about: "Pressure from the equation of state.",
    source: Source::Derived { from: &["rho"], values: pressures },
};

/// The stages of an evaluation.
const EVALUATE: [Stage; 4] = [Stage::Sort, Stage::Density, Stage::PreForce, Stage::Force];

/// One step with the model's integrator.
fn step(clock: &mut Clock, s: &mut dyn Stages) -> Result<StepReport, Halted> {
    let model: &Model = s.model();
    let (integrator, n) = (model.integrator, model.particle_count());
    let (dt, m, solves) = match integrator {
        Integrator::SymplecticEuler => {
            let m = clock.evaluate(s, &EVALUATE)?;
            let dt = clock.dt(s.model(), &m, 0.0)?;
            let keep = clock.keep(s.model(), dt);
            s.kick(dt, keep);
            let mut solves = velocity_solves(clock, s, dt)?;
            s.run(Stage::Kick, dt);
            s.drift(dt);
            s.run(Stage::Drift, dt);
            solves.extend(position_solve::run(clock, s, dt)?);
            (dt, m, solves)
        }
        Integrator::Leapfrog => {
            let m0 = match clock.measures() {
                Some(m) => m,
                None => clock.evaluate(s, &EVALUATE)?,
            };
            let dt = clock.dt(s.model(), &m0, 0.0)?;
            let half: Real = 0.5 * dt;
            let keep = clock.keep(s.model(), half);
            s.kick(half, keep);
            s.drift(dt);
            s.run(Stage::Drift, dt);
            let mut solves = position_solve::run(clock, s, dt)?;
            let m = clock.evaluate(s, &EVALUATE)?;
            s.kick(half, keep);
            solves.extend(velocity_solves(clock, s, dt)?);
            s.run(Stage::Kick, dt);
            (dt, m, solves)
        }
    };
    s.run(Stage::PostStep, dt);
    s.end_step();
    Ok(clock.advance(dt, &m, n, solves))
}

/// Pressures (Pa) of particles with densities `columns[0]` (and materials
/// `columns[1]` in scenes with several): the `pressure` channel.
pub fn pressures(model: &Model, columns: &[crate::attrs::Column]) -> Vec<f32> {
    use crate::attrs::Column;
    let eos = &model.consts::<WcsphConsts>().eos;
    match columns {
        [Column::F32(rho)] => rho.iter().map(|&r| eos[0].pressure(r)).collect(),
        [Column::F32(rho), Column::U32(mat)] => {
            rho.iter().zip(mat).map(|(&r, &m)| eos[m as usize].pressure(r)).collect()
        }
        _ => panic!("pressures: densities (and materials) expected"),
    }
}
