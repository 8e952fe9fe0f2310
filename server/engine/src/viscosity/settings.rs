//! The settings of the per-particle viscosity's force, which the module that sets
//! the viscosity takes in its section (`snow.solver`, `heat.viscous_solver`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The integration of the per-particle viscous force ([`super`]), chosen
/// by the module that sets the per-particle viscosity (`snow.solver`, `heat.viscous_solver`).
/// Implicit is the default: measured, it reaches the snow module's channel
/// profiles 7 to 65 times faster and runs the avalanche at 256k particles 2.4 times
/// faster on the CPU (docs/snow.md, docs/benchmarks.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "method", rename_all = "snake_case", deny_unknown_fields)]
pub enum ViscousSolver {
    /// The force of the velocities at the start of the step; dt at most
    /// `0.125 h^2 rho0 / max_viscosity` (Morris et al. 1997, eq. 20).
    Explicit,
    /// Backward Euler (Weiler et al. 2018): `(M + dt K) v = M v*`, K the viscous
    /// operator at the step's viscosities, by Jacobi-preconditioned conjugate
    /// gradients.
    Implicit {
        /// Relative residual `|r| / |b|` (in the preconditioner's norm) to reach.
        #[serde(default = "default_tolerance")]
        tolerance: f32,
        /// Iterations at most; a solve not converged by then halts the scene.
        #[serde(default = "default_max_iterations")]
        max_iterations: u32,
    },
}

impl Default for ViscousSolver {
    fn default() -> Self {
        ViscousSolver::Implicit { tolerance: default_tolerance(), max_iterations: default_max_iterations() }
    }
}

fn default_tolerance() -> f32 {
    1e-3
}

fn default_max_iterations() -> u32 {
    200
}

/// The viscous condition at walls.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WallShear {
    /// Zero velocity on the wall surface.
    #[default]
    NoSlip,
    /// No shear stress from walls.
    Slip,
}
