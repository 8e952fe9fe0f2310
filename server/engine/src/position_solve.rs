//! Position-level solves: a module's iterative solve over predicted positions
//! (position-based dynamics, Mueller et al. 2007, alg. 1 lines 5-9; the cluster
//! solvers of shape matching). The core keeps a copy of the predicted positions
//! (`core.predict`), the modules' solves move the positions iteration by iteration
//! ([`crate::scheme::Iterate`], with its sweeps: e.g. one per colour of a
//! Gauss-Seidel sweep, the colour handed to the passes as the sweep index), and the
//! velocities follow what the solves moved (`core.velocity_from_positions`,
//! `v += (x - x_predicted) / dt`). Then a module's velocity corrections run
//! (`ModelBuilder::after_position_solves`: the solid's clusters' velocities damped
//! toward their rigid motions). Iterations and residuals go into the step report
//! with the other solves.
//!
//! When the solves run is the scheme's ([`When`]):
//! - [`When::AfterDrift`] (WCSPH): over the positions the scheme's drift predicted,
//!   which they then move ([`run`]);
//! - [`When::BeforeDensitySolve`] (DFSPH): as a velocity correction before the
//!   constant-density solve ([`run_ahead`]): over the positions the velocities after
//!   the kick would reach (`core.look_ahead`), which are then put back
//!   (`core.look_back`), so that the pressure solve sees the velocities the solves
//!   ask for and removes the compression they would make against walls, fluid or
//!   other bodies within the same step. Run after the drift at DFSPH's step, a body
//!   landing on the floor pressed its lowest layer into the walls, which the next
//!   step's solve found at 52 % compression (docs/solid.md, "At the flow's step").
//!
//! A scene without a position solve has none of the passes, nor `x_predicted`
//! and `x_start`.

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::clock::Clock;
use crate::cpu::{CpuCx, CpuPass};
use crate::guard::Halted;
use crate::math::{Real, Vec3};
use crate::plan::PassSpec;
use crate::scheme::{Solve, Stages};
use rayon::prelude::*;

/// The positions the drift predicted, before the solves moved them.
pub static X_PREDICTED: AttrSpec = AttrSpec {
    name: "x_predicted",
    elem: Elem::Vec3,
    unit: "m",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "core",
    about: "Positions predicted by the drift, before the position solves.",
};

/// Keeps the predicted positions.
pub static PREDICT: PassSpec = PassSpec::solve("core", "core.predict", &["x"], &["x_predicted"], &[]);

/// `v += (x - x_predicted) / dt`.
pub static VELOCITY_FROM_POSITIONS: PassSpec =
    PassSpec::solve("core", "core.velocity_from_positions", &["x", "x_predicted"], &[], &["v"]);

/// The positions before a look-ahead ([`run_ahead`]), put back after the solves.
pub static X_START: AttrSpec = AttrSpec {
    name: "x_start",
    elem: Elem::Vec3,
    unit: "m",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "core",
    about: "Positions before the position solves' look-ahead, put back after them.",
};

/// `x_start = x`, then `x += dt v`.
pub static LOOK_AHEAD: PassSpec = PassSpec::solve("core", "core.look_ahead", &["v"], &["x_start"], &["x"]);

/// `x = x_start`.
pub static LOOK_BACK: PassSpec = PassSpec::solve("core", "core.look_back", &["x_start"], &[], &["x"]);

/// When a scheme runs the position solves in its step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum When {
    /// Over the positions the drift predicted ([`run`]).
    AfterDrift,
    /// As a velocity correction before the constant-density solve ([`run_ahead`]).
    BeforeDensitySolve,
}

/// The CPU halves.
pub static CPU: &[(&str, &dyn CpuPass)] = &[
    ("core.predict", &Predict),
    ("core.velocity_from_positions", &VelocityFromPositions),
    ("core.look_ahead", &LookAhead),
    ("core.look_back", &LookBack),
];

/// Runs the model's position solves over the current positions, in the order the
/// modules declared them, the velocities following what they moved, then the
/// velocity corrections after them over the solved positions; a solve that does
/// not converge halts the scene.
pub fn run(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    let mut done = solve(clock, s, dt)?;
    done.extend(after(clock, s, dt)?);
    Ok(done)
}

/// Runs the position solves and the corrections after them ([`run`]) over the
/// positions a drift of `dt` with the current velocities would reach, then puts the
/// positions back: they act on the velocities only (a scheme whose pressure solve
/// follows them, [`When`]).
pub fn run_ahead(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    if s.model().position_solves.is_empty() {
        return Ok(Vec::new());
    }
    s.run_pass(LOOK_AHEAD.name, dt);
    let done = run(clock, s, dt);
    s.run_pass(LOOK_BACK.name, dt);
    done
}

/// The solves and the velocities' update.
fn solve(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    let solves = s.model().position_solves.clone();
    if solves.is_empty() {
        return Ok(Vec::new());
    }
    s.run_pass(PREDICT.name, dt);
    let done = solves.iter().map(|v| v.run(s, dt).map_err(|e| clock.halt(e, None))).collect::<Result<_, _>>()?;
    if dt > 0.0 {
        s.run_pass(VELOCITY_FROM_POSITIONS.name, dt);
    }
    Ok(done)
}

/// The velocity corrections after the solves (none in a step of 0 s).
fn after(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    if dt <= 0.0 {
        return Ok(Vec::new());
    }
    let after = s.model().after_position_solves.clone();
    after.iter().map(|a| a.run(s, dt).map_err(|e| clock.halt(e, None))).collect()
}

#[derive(Debug)]
struct Predict;

impl CpuPass for Predict {
    fn run(&self, cx: &mut CpuCx<'_>) {
        copy(cx, "x", "x_predicted");
    }
}

/// Copies the positions attribute `from` into `to`.
fn copy(cx: &mut CpuCx<'_>, from: &str, to: &str) {
    let (from, to) = (cx.attrs.handle::<Vec3>(from), cx.attrs.handle::<Vec3>(to));
    let mut out = cx.attrs.take(to);
    out.copy_from_slice(cx.attrs.get(from));
    cx.attrs.put(to, out);
}

#[derive(Debug)]
struct VelocityFromPositions;

impl CpuPass for VelocityFromPositions {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let inv_dt = 1.0 / cx.dt;
        let (x, p, v) =
            (cx.attrs.handle::<Vec3>("x"), cx.attrs.handle::<Vec3>("x_predicted"), cx.attrs.handle::<Vec3>("v"));
        let mut vel = cx.attrs.take(v);
        let (pos, predicted) = (cx.attrs.get(x), cx.attrs.get(p));
        vel.par_iter_mut().enumerate().with_min_len(4096).for_each(|(i, v)| *v += (pos[i] - predicted[i]) * inv_dt);
        cx.attrs.put(v, vel);
    }
}

#[derive(Debug)]
struct LookAhead;

impl CpuPass for LookAhead {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let (x, start, v) =
            (cx.attrs.handle::<Vec3>("x"), cx.attrs.handle::<Vec3>("x_start"), cx.attrs.handle::<Vec3>("v"));
        let (mut pos, mut kept) = (cx.attrs.take(x), cx.attrs.take(start));
        kept.copy_from_slice(&pos);
        let vel = cx.attrs.get(v);
        pos.par_iter_mut().zip(vel.par_iter()).with_min_len(4096).for_each(|(x, v)| *x += *v * dt);
        cx.attrs.put(x, pos);
        cx.attrs.put(start, kept);
    }
}

#[derive(Debug)]
struct LookBack;

impl CpuPass for LookBack {
    fn run(&self, cx: &mut CpuCx<'_>) {
        copy(cx, "x_start", "x");
    }
}
