//! Validation cases with their references (docs/validation/cases.md): the
//! measurements a test, a benchmark or `floe validate` needs.
//!
//! - [`dam_break`], [`hydrostatic`], [`poiseuille`], [`taylor_green`]: reference solutions and error measures.
//! - [`cases`]: each case run at one resolution and option, timed, with its errors.
//! - [`stability`]: the battery of stiff and extreme scenes.
//! - [`energy`]: mechanical energy, for energy-growth checks.

pub mod cases;
pub mod dam_break;
pub mod energy;
pub mod hydrostatic;
pub mod poiseuille;
pub mod stability;
pub mod taylor_green;

use crate::Simulation;
use crate::guard::Halted;
use std::time::Instant;

/// Steps `sim` to `t_end` (s), calling `probe` at t = 0 and every `every` seconds
/// of simulated time. Returns the wall seconds spent stepping (probes excluded)
/// and the halt, if the scene halted.
pub fn run_probed(
    sim: &mut Simulation,
    t_end: f64,
    every: f64,
    mut probe: impl FnMut(&Simulation),
) -> (f64, Option<Halted>) {
    probe(sim);
    let mut next = every;
    let mut wall = 0.0;
    while sim.time() < t_end {
        let t0 = Instant::now();
        let step = sim.step();
        wall += t0.elapsed().as_secs_f64();
        if let Err(h) = step {
            return (wall, Some(h));
        }
        if sim.time() >= next {
            probe(sim);
            next += every;
        }
    }
    (wall, None)
}
