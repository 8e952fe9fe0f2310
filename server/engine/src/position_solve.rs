//! Position-level solves: a module's iterative solve over predicted positions
//! (position-based dynamics, Mueller et al. 2007, alg. 1 lines 5-9; the cluster
//! solvers of shape matching). After the scheme's drift has predicted every
//! position, the core keeps a copy (`core.predict`), the modules' solves move the
//! positions iteration by iteration ([`crate::scheme::Iterate`], with its
//! sweeps: e.g. one per colour of a Gauss-Seidel sweep, the colour handed to the
//! passes as the sweep index), and the velocities follow what the solves moved
//! (`core.velocity_from_positions`, `v += (x - x_predicted) / dt`), so the next
//! step starts from velocities consistent with the corrected positions. Iterations
//! and residuals go into the step report with the other solves.
//!
//! A scene without a position solve has neither the passes nor `x_predicted`.

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

/// The CPU halves.
pub static CPU: &[(&str, &dyn CpuPass)] =
    &[("core.predict", &Predict), ("core.velocity_from_positions", &VelocityFromPositions)];

/// Runs the model's position solves after a drift of `dt`, in the order the
/// modules declared them; a solve that does not converge halts the scene.
pub fn run(clock: &Clock, s: &mut dyn Stages, dt: Real) -> Result<Vec<Solve>, Halted> {
    let solves = s.model().position_solves.clone();
    if solves.is_empty() {
        return Ok(Vec::new());
    }
    s.run_pass(PREDICT.name, dt);
    let done = solves.iter().map(|v| v.run(s, dt).map_err(|e| clock.halt(e, None))).collect();
    if dt > 0.0 {
        s.run_pass(VELOCITY_FROM_POSITIONS.name, dt);
    }
    done
}

#[derive(Debug)]
struct Predict;

impl CpuPass for Predict {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (x, p) = (cx.attrs.handle::<Vec3>("x"), cx.attrs.handle::<Vec3>("x_predicted"));
        let mut predicted = cx.attrs.take(p);
        predicted.copy_from_slice(cx.attrs.get(x));
        cx.attrs.put(p, predicted);
    }
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
