//! Divergence-free SPH (Bender & Koschier 2015, "Divergence-free smoothed particle
//! hydrodynamics", SCA; 2017, "Divergence-free SPH for incompressible and viscous
//! fluids", IEEE TVCG 23(3)): pressure from two iterative solves per step instead of
//! an equation of state, so steps are limited by the flow speed, not by sound.
//!
//! A step:
//! 1. sort, density and the factor `alpha` of each particle (`dfsph.factor`), the
//!    non-pressure forces (the fluid module's pass without pressure), measure, dt
//!    from the CFL condition on the flow speed;
//! 2. the divergence-free solve: the velocities are corrected until the mean
//!    compression rate `dt (Drho/Dt) / rho0` is at most
//!    `solver.dfsph.divergence_tolerance` (B&K 2017, algorithm 2);
//! 3. the kick `v += dt a` with the non-pressure accelerations, the modules'
//!    velocity solves (implicit viscosity) and the kick-stage passes, then the
//!    modules' position solves as a velocity correction over the positions the
//!    velocities would reach (the solid's shape matching;
//!    [`crate::position_solve::When::BeforeDensitySolve`]);
//! 4. the constant-density solve: the velocities are corrected until the mean
//!    predicted compression `(rho + dt Drho/Dt - rho0) / rho0` is at most
//!    `solver.dfsph.density_tolerance` (algorithm 3);
//! 5. the drift `x += dt v`; with the CG in a closed scene, the particle shift
//!    ([`cg`], `solver.dfsph.shift`).
//!
//! Step 2 corrects the velocities the last drift left at the positions this step
//! sorted: the divergence-free solve B&K run at the end of a step, after its
//! neighbour search, run before the next step's kick (the non-pressure forces see the
//! velocities before it).
//!
//! Each solve is a Jacobi iteration (the default; `solver.dfsph.solver = "cg"` takes
//! conjugate gradients instead, with mirrored walls: [`cg`]) on the stiffness of each
//! particle, written as the
//! pressure term `P = p / rho^2` that the pressure force uses (the quantity WCSPH's
//! `pterm` holds):
//! `a_i = -sum_j (m_i P_i + m_j^2 P_j / m_i) grad W_ij - P_i sum_b psi_b grad W_ib`
//! (Solenthaler & Pajarola's multi-material form, Akinci's wall term). With
//! `s_i = m_i sum_j grad W_ij + sum_b psi_b grad W_ib` the diagonal of the system is
//! `D_i = |s_i|^2 + m_i^3 sum_j |grad W_ij|^2 / m_j` (B&K's factor, eq. 9 of 2017,
//! written for P) and `alpha_i = 1 / D_i`. An iteration computes each particle's error
//! `e_i` from the current velocities and its increment `dP_i` (`e alpha / dt^2` for
//! the density, `e alpha / dt` for the divergence); the next kick applies the
//! increments' pressure force to the velocities and adds them to the stiffness, so
//! the stiffness is exactly what was applied. Only compression is corrected
//! (`e >= 0`): a free surface is never pulled together, and the stiffness only
//! grows within a step (as in SPlisHSPlasH); a Jacobi update with signed errors,
//! measured on the resting column, oscillates and diverges. Particles with fewer than
//! [`FULL_NEIGHBOURHOOD`] neighbours are left out of the divergence solve, as in
//! SPlisHSPlasH: at a splash's edge the divergence says nothing about compression.
//!
//! Warm start: each solve starts from the stiffness it ended the previous step with
//! (`kappa`, `kappa_v`, state attributes: sorted with the particles and saved in
//! snapshots, so a restored scene continues bit for bit), scaled by
//! [`WARM_START`], applied as a first kick before the first residual. The
//! stiffness is kept as `p / rho^2` of the step it was found in; dt changes
//! slowly under the CFL condition, so it is not rescaled.

pub mod cg;
pub mod cg_cpu;
pub mod cpu;
pub mod spec;

use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use crate::channels::{ChannelSpec, Source};
use crate::clock::Clock;
use crate::guard::Halted;
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::plan::{PassSpec, Stage};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scheme::{Iterate, Op, ReduceOp, Reduction, SchemeDef, Stages, StepReport, velocity_solves};
use spec::{DfsphSettings, DfsphSolver};

/// The scheme's definition.
pub static SCHEME: SchemeDef = SchemeDef {
    id: "dfsph",
    about: "Divergence-free SPH: a divergence-free and a constant-density solve per step, steps at the flow's CFL limit.",
    build,
    settings: &[SectionDef::defaulted::<DfsphSettings>(SETTINGS)],
    pressure_terms: false,
    validate,
    retune: |scene, model| model.set_consts(DfsphConsts::of(settings(scene))),
    cpu: &[
        ("dfsph.factor", &cpu::Factor),
        ("dfsph.divergence_warm", &cpu::Warm { kappa: "kappa_v", increment: "dkappa_v" }),
        ("dfsph.divergence_kick", &cpu::Kick { kappa: "kappa_v", increment: "dkappa_v" }),
        ("dfsph.divergence_error", &cpu::Error { density: false }),
        ("dfsph.density_warm", &cpu::Warm { kappa: "kappa", increment: "dkappa" }),
        ("dfsph.density_kick", &cpu::Kick { kappa: "kappa", increment: "dkappa" }),
        ("dfsph.density_error", &cpu::Error { density: true }),
        ("dfsph.cg_held", &cg_cpu::Held),
        ("dfsph.cg_closed", &cg_cpu::Closed),
        ("dfsph.cg_shift", &cg_cpu::Shift),
        ("dfsph.cg_shift_apply", &cg_cpu::ShiftApply),
        ("dfsph.cg_wall_pressure", &cg_cpu::WallPressure),
        ("dfsph.cg_divergence_warm", &cg_cpu::Warm(cpu::Warm { kappa: "kappa_v", increment: "dkappa_v" })),
        ("dfsph.cg_divergence_start", &cg_cpu::Start { density: false }),
        ("dfsph.cg_divergence_adjust", &cg_cpu::Adjust { density: false }),
        ("dfsph.cg_divergence_residual", &cg_cpu::Residual { residual: "divergence_error" }),
        ("dfsph.cg_divergence_update", &cg_cpu::Update { kappa: "kappa_v" }),
        ("dfsph.cg_divergence_clamp", &cg_cpu::Clamp { kappa: "kappa_v", increment: "dkappa_v" }),
        ("dfsph.cg_density_warm", &cg_cpu::Warm(cpu::Warm { kappa: "kappa", increment: "dkappa" })),
        ("dfsph.cg_density_start", &cg_cpu::Start { density: true }),
        ("dfsph.cg_density_adjust", &cg_cpu::Adjust { density: true }),
        ("dfsph.cg_density_residual", &cg_cpu::Residual { residual: "density_error" }),
        ("dfsph.cg_density_update", &cg_cpu::Update { kappa: "kappa" }),
        ("dfsph.cg_density_clamp", &cg_cpu::Clamp { kappa: "kappa", increment: "dkappa" }),
        ("dfsph.cg_gradient", &cg_cpu::Gradient),
        ("dfsph.cg_product", &cg_cpu::Product),
        ("dfsph.cg_direction", &cg_cpu::Direction),
    ],
    step,
    signal_speed: |_| 0.0,
    position_solves: crate::position_solve::When::BeforeDensitySolve,
};

/// Fraction of the previous step's stiffness each solve starts from. The
/// iterations only add to the stiffness, so a full warm start would let it grow
/// from step to step; half (SPlisHSPlasH's choice) keeps it bounded.
pub const WARM_START: Real = 0.5;

/// Neighbours (fluid and wall, the particle itself not counted) a particle needs to
/// take part in the divergence-free solve (SPlisHSPlasH's choice for 3D; a full
/// lattice neighbourhood at the default support holds 26).
pub const FULL_NEIGHBOURHOOD: u32 = 20;

/// The solves' settings.
#[derive(Debug, Clone, Copy)]
pub struct DfsphConsts {
    /// Tolerances, the iteration limit and the solver.
    pub settings: DfsphSettings,
    /// The walls' factor `c` in the pressure force and the density rate: 1 for
    /// Akinci's one-sided walls (the Jacobi), 2 for mirrored walls (the CG, [`cg`]).
    pub wall_factor: Real,
}

impl DfsphConsts {
    /// The constants of `settings`.
    pub fn of(settings: DfsphSettings) -> Self {
        let wall_factor = match settings.solver {
            DfsphSolver::Jacobi => 1.0,
            DfsphSolver::Cg => 2.0,
        };
        Self { settings, wall_factor }
    }
}

const fn attr(name: &'static str, unit: &'static str, role: Role, about: &'static str) -> AttrSpec {
    AttrSpec { name, elem: Elem::F32, unit, role, added_later: false, space: PARTICLES, module: "dfsph", about }
}

/// The factor `alpha = 1 / D` of each particle.
pub static ALPHA: AttrSpec =
    attr("alpha", "m^8/kg^2", Role::Derived, "DFSPH factor: the inverse diagonal of the solve.");
/// Stiffness of the constant-density solve, `p / rho^2`, summed over its iterations.
pub static KAPPA: AttrSpec =
    attr("kappa", "m^5/(kg s^2)", Role::State, "Constant-density solve's stiffness p/rho^2 (warm start).");
/// Stiffness of the divergence-free solve, `p / rho^2`, summed over its iterations.
pub static KAPPA_V: AttrSpec =
    attr("kappa_v", "m^5/(kg s^2)", Role::State, "Divergence-free solve's stiffness p/rho^2 (warm start).");
/// The constant-density solve's increment of the current iteration.
pub static DKAPPA: AttrSpec = attr("dkappa", "m^5/(kg s^2)", Role::Derived, "Constant-density solve's increment.");
/// The divergence-free solve's increment of the current iteration.
pub static DKAPPA_V: AttrSpec = attr("dkappa_v", "m^5/(kg s^2)", Role::Derived, "Divergence-free solve's increment.");
/// Predicted compression `max(rho + dt Drho/Dt - rho0, 0) / rho0`: the density residual.
pub static DENSITY_ERROR: AttrSpec =
    attr("density_error", "", Role::Derived, "Predicted relative compression (the density solve's residual).");
/// Compression in one step `dt max(Drho/Dt, 0) / rho0`: the divergence residual.
pub static DIVERGENCE_ERROR: AttrSpec =
    attr("divergence_error", "", Role::Derived, "Relative compression per step (the divergence solve's residual).");

/// `alpha` from the step's neighbours.
pub static FACTOR: PassSpec = PassSpec {
    name: "dfsph.factor",
    module: "dfsph",
    stage: Stage::Density,
    reads: &["x"],
    writes: &["alpha"],
    accumulates: &[],
    tolerance: 1e-4,
};
/// The divergence solve's warm start: `dkappa_v = w kappa_v`, `kappa_v = dkappa_v`.
pub static DIVERGENCE_WARM: PassSpec =
    PassSpec::solve("dfsph", "dfsph.divergence_warm", &["kappa_v"], &["dkappa_v", "kappa_v"], &[]);
/// The pressure force of the divergence increments, as a kick; the increments are
/// added to the stiffness.
pub static DIVERGENCE_KICK: PassSpec =
    PassSpec::solve("dfsph", "dfsph.divergence_kick", &["x", "dkappa_v"], &[], &["v", "kappa_v"]);
/// The compression rate, its increment and residual.
pub static DIVERGENCE_ERROR_PASS: PassSpec = PassSpec::solve(
    "dfsph",
    "dfsph.divergence_error",
    &["x", "v", "rho", "alpha"],
    &["dkappa_v", "divergence_error"],
    &[],
);
/// The density solve's warm start.
pub static DENSITY_WARM: PassSpec =
    PassSpec::solve("dfsph", "dfsph.density_warm", &["kappa"], &["dkappa", "kappa"], &[]);
/// The pressure force of the density increments, as a kick; the increments are
/// added to the stiffness.
pub static DENSITY_KICK: PassSpec =
    PassSpec::solve("dfsph", "dfsph.density_kick", &["x", "dkappa"], &[], &["v", "kappa"]);
/// The predicted compression, its increment and residual.
pub static DENSITY_ERROR_PASS: PassSpec =
    PassSpec::solve("dfsph", "dfsph.density_error", &["x", "v", "rho", "alpha"], &["dkappa", "density_error"], &[]);

/// Pressure `rho^2 (kappa + kappa_v)` (Pa): the pressure of both solves' forces.
pub const PRESSURE: ChannelSpec = ChannelSpec {
    name: "pressure",
    unit: "Pa",
    components: 1,
    exact: false,
    set: crate::channels::PARTICLES,
    module: "dfsph",
    about: "Pressure of the last step's solves, rho^2 (kappa + kappa_v).",
    source: Source::Derived { from: &["rho", "kappa", "kappa_v"], values: pressures },
};

/// The pressure needs no material: the materials' column, which follows the three
/// inputs in scenes of several fluids, is ignored.
fn pressures(_: &Model, columns: &[Column]) -> Vec<f32> {
    match columns {
        [Column::F32(rho), Column::F32(k), Column::F32(kv), ..] => {
            rho.iter().zip(k).zip(kv).map(|((&r, &k), &kv)| r * r * (k + kv)).collect()
        }
        _ => panic!("pressures: densities and stiffnesses expected"),
    }
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let consts = DfsphConsts::of(settings(scene));
    b.set_consts(consts);
    for spec in [&ALPHA, &KAPPA_V, &DKAPPA, &DKAPPA_V, &DENSITY_ERROR, &DIVERGENCE_ERROR] {
        b.zeros(spec);
    }
    match consts.settings.solver {
        DfsphSolver::Jacobi => b.zeros(&KAPPA),
        DfsphSolver::Cg => b.attr(&KAPPA, Column::F32(stiffness_at_rest(b))),
    }
    b.pass(&FACTOR);
    match consts.settings.solver {
        DfsphSolver::Jacobi => {
            for pass in [
                &DIVERGENCE_WARM,
                &DIVERGENCE_KICK,
                &DIVERGENCE_ERROR_PASS,
                &DENSITY_WARM,
                &DENSITY_KICK,
                &DENSITY_ERROR_PASS,
            ] {
                b.pass(pass);
            }
        }
        DfsphSolver::Cg => {
            let masses: Vec<Real> = b.materials().iter().map(|m| m.mass).collect();
            if masses.iter().any(|&m| m != masses[0]) {
                return Err(BuildError::Setting(format!(
                    "solver.dfsph.solver: \"cg\" needs particles of one mass (its system is symmetric only then); \
                     this scene's materials have masses {masses:?} kg: use \"jacobi\""
                )));
            }
            b.space(cg::SPACE, cg::SLOTS);
            for spec in cg::ATTRS {
                b.zeros(spec);
            }
            b.space(cg::CLOSED_SPACE, 1);
            b.attr(&cg::CLOSED, Column::F32(vec![cg::UNDECIDED]));
            for pass in cg::PASSES {
                b.pass(pass);
            }
            if consts.settings.shift > 0.0 {
                b.zeros(&cg::SHIFT);
                for pass in cg::SHIFT_PASSES {
                    b.pass(pass);
                }
            }
        }
    }
    b.channel(PRESSURE);
    Ok(())
}

/// The solves' settings in `solver` ([`DfsphSettings`]).
pub const SETTINGS: &str = "dfsph";

/// The scene's DFSPH settings.
pub fn settings(scene: &Scene) -> DfsphSettings {
    scene.solver.settings(SETTINGS).unwrap_or_default()
}

/// Checks the tolerances and the iteration limit (any scene may carry them: every
/// scene's `solver` has them, with their defaults).
fn validate(scene: &Scene, _: bool, c: &mut crate::scene::validate::Checker) {
    let s = settings(scene);
    c.within("solver.dfsph.density_tolerance", s.density_tolerance, 1e-6, 0.1);
    c.within("solver.dfsph.divergence_tolerance", s.divergence_tolerance, 1e-6, 0.1);
    c.within("solver.dfsph.max_iterations", s.max_iterations as f32, 1.0, 10_000.0);
    c.within("solver.dfsph.shift", s.shift, 0.0, 8.0);
    if s.compact_gradients && scene.solver.kernel == crate::kernel::KernelKind::Mueller {
        c.fail(
            "solver.dfsph.compact_gradients",
            "needs solver.kernel = \"cubic_spline\" or \"wendland_c2\" (the spiky gradient over r is unbounded near r = 0)"
                .into(),
        );
    }
}

/// The divergence-free solve with the scene's settings.
pub fn divergence_solve(s: &DfsphSettings) -> Iterate {
    if s.solver == DfsphSolver::Cg {
        return cg::divergence_solve(s);
    }
    Iterate {
        name: "dfsph.divergence",
        start: &[
            Op::Pass("dfsph.divergence_warm"),
            Op::Pass("dfsph.divergence_kick"),
            Op::Pass("dfsph.divergence_error"),
        ],
        iteration: &[Op::Pass("dfsph.divergence_kick"), Op::Pass("dfsph.divergence_error")],
        residual: Reduction { attr: "divergence_error", op: ReduceOp::Mean },
        tolerance: f64::from(s.divergence_tolerance),
        min: 1,
        max: s.max_iterations,
        check_every: 1,
        sweeps: 1,
        max_sweeps: 1,
    }
}

/// The constant-density solve with the scene's settings.
pub fn density_solve(s: &DfsphSettings) -> Iterate {
    if s.solver == DfsphSolver::Cg {
        return cg::density_solve(s);
    }
    Iterate {
        name: "dfsph.density",
        start: &[Op::Pass("dfsph.density_warm"), Op::Pass("dfsph.density_kick"), Op::Pass("dfsph.density_error")],
        iteration: &[Op::Pass("dfsph.density_kick"), Op::Pass("dfsph.density_error")],
        residual: Reduction { attr: "density_error", op: ReduceOp::Mean },
        tolerance: f64::from(s.density_tolerance),
        min: 2,
        max: s.max_iterations,
        check_every: 1,
        sweeps: 1,
        max_sweeps: 1,
    }
}

/// Each particle's stiffness `p / rho0^2` under the weight of the fluid above it
/// ([`crate::overburden`]), which the CG's first density solve starts from: a fluid
/// at rest starts in balance instead of falling onto its own compression. From
/// zero, that first solve builds the whole hydrostatic pressure in one step, and
/// its error disorders the particles, which the CG's carried stiffness then keeps
/// (docs/validation/schemes/CG.md: the resting column at 0.025 m 0.026 against
/// 0.041, the dam break's front RMS 0.124 against 0.223). The Jacobi starts from
/// zero: it carries half its stiffness from step to step, so a start decays within
/// a few steps, and measured no better (the dam break at 21,952 particles: front
/// RMS 0.242 against 0.228).
fn stiffness_at_rest(b: &ModelBuilder) -> Vec<Real> {
    let at_rest = crate::overburden::at_rest(b);
    let rest: Vec<Real> = b.materials().iter().map(|m| m.rest_density).collect();
    at_rest.pressure.iter().zip(&at_rest.material).map(|(&p, &m)| p / (rest[m as usize] * rest[m as usize])).collect()
}

/// The stages before the solves.
const EVALUATE: [Stage; 4] = [Stage::Sort, Stage::Density, Stage::PreForce, Stage::Force];

/// One step (see the module's documentation).
fn step(clock: &mut Clock, s: &mut dyn Stages) -> Result<StepReport, Halted> {
    let n = s.model().particle_count();
    let settings = s.model().consts::<DfsphConsts>().settings;
    let m = clock.evaluate(s, &EVALUATE)?;
    let held = held_particles(&settings, s).map_err(|e| clock.halt(e, None))?;
    let c_p = pressure_speed(held, s).map_err(|e| clock.halt(e, None))?;
    let dt = clock.dt(s.model(), &m, c_p)?;
    let divergence = divergence_solve(&settings).run(s, dt).map_err(|e| clock.halt(e, None))?;
    finish(&settings, cg::DIVERGENCE_FINISH, s, dt);
    let keep = clock.keep(s.model(), dt);
    s.kick(dt, keep);
    let mut solves = vec![divergence];
    solves.extend(velocity_solves(clock, s, dt)?);
    s.run(Stage::Kick, dt);
    solves.extend(crate::position_solve::run_ahead(clock, s, dt)?);
    solves.push(density_solve(&settings).run(s, dt).map_err(|e| clock.halt(e, None))?);
    finish(&settings, cg::DENSITY_FINISH, s, dt);
    s.drift(dt);
    if held == Some(0.0) && settings.shift > 0.0 {
        let reach = m.max_speed2.0.sqrt() * dt;
        for &op in cg::SHIFT_OPS {
            op.run(s, reach);
        }
    }
    s.run(Stage::Drift, dt);
    s.run(Stage::PostStep, dt);
    s.end_step();
    Ok(clock.advance(dt, &m, n, solves))
}

/// The CG's held test ([`cg::HELD_OPS`]) and the number of particles it held (none
/// in a closed scene); None for the Jacobi.
fn held_particles(settings: &DfsphSettings, s: &mut dyn Stages) -> Result<Option<f64>, String> {
    if settings.solver != DfsphSolver::Cg {
        return Ok(None);
    }
    for &op in cg::HELD_OPS {
        op.run(s, 0.0);
    }
    s.reduce(&Reduction { attr: cg::HELD_ATTR.name, op: ReduceOp::Sum }).map(Some)
}

/// The pressure's signal speed `sqrt(p / rho)` (m/s) for the step's limit
/// ([`crate::timestep::Limits::c_p`]) with the CG at a free surface (`held`
/// particles, [`held_particles`]): from the largest stiffness `P = p / rho^2` the
/// last constant-density solve left, at the largest rest density. Without it the
/// CG's resting column at 0.01875 m grows a disorder from its floor at the 5 ms cap
/// (pressure L2 0.18); its steps are stable below 0.6 to 0.7 `h / c_p` on columns
/// of 0.45 and 0.9 m at 0.025 and 0.01875 m (docs/validation/schemes/CG.md). None
/// (0) where no particle is held (a closed domain, whose stiffness's level is free:
/// the vortex halted under it) and for the Jacobi (its column stops converging under
/// it, its Akinci walls needing twice the pressure beside a wall, and the dam break
/// takes a quarter more steps).
fn pressure_speed(held: Option<f64>, s: &mut dyn Stages) -> Result<Real, String> {
    if held.unwrap_or(0.0) == 0.0 {
        return Ok(0.0);
    }
    let kappa = s.reduce(&Reduction { attr: "kappa", op: ReduceOp::Max })?.max(0.0);
    let rho0 = s.model().materials.iter().map(|m| m.rest_density).fold(0.0, Real::max);
    Ok((kappa * f64::from(rho0)).sqrt() as Real)
}

/// What the CG runs after a solve (the clamp at a free surface); the Jacobi nothing.
fn finish(settings: &DfsphSettings, ops: &[Op], s: &mut dyn Stages, dt: Real) {
    if settings.solver == DfsphSolver::Cg {
        for &op in ops {
            op.run(s, dt);
        }
    }
}
