//! The pressure solvers shipped with the engine, each a folder of its own that knows
//! the core ([`crate::scheme`] is what a scheme is), never a module. They are
//! registered in [`crate::registry`].
//!
//! - [`wcsph`]: weakly compressible SPH.
//! - [`dfsph`]: divergence-free SPH, two iterative pressure solves per step.

pub mod dfsph;
pub mod wcsph;
