//! DFSPH's settings in a scene's `solver` table: `dfsph`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// DFSPH's two solves (Bender & Koschier 2017): each iterates until its mean
/// relative error is at most its tolerance, and halts the scene if it is not there
/// after `max_iterations`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DfsphSettings {
    /// Largest mean predicted density error `(rho* - rho0) / rho0` (compression only)
    /// the constant-density solve leaves: 0.001 is 0.1 %.
    #[serde(default = "default_density_tolerance")]
    pub density_tolerance: f32,
    /// Largest mean density change per step `dt (Drho/Dt) / rho0` (compression only)
    /// the divergence-free solve leaves: 0.001 is 0.1 % per step.
    #[serde(default = "default_divergence_tolerance")]
    pub divergence_tolerance: f32,
    /// Most iterations of each solve in one step (1 to 10000).
    #[serde(default = "default_max_iterations")]
    pub max_iterations: u32,
    /// The CPU backend keeps each neighbour pair's kernel gradient for the step's
    /// solves: 12 bytes a pair (about 740 bytes a particle in all), or with `true` 2
    /// bytes a pair (about 360), each solve iteration then about 1.3 times as long.
    /// Needs the cubic spline kernel. The GPU keeps none either way.
    #[serde(default)]
    pub compact_gradients: bool,
    /// How both solves iterate: `"jacobi"` (B&K's, compression only; the default) or
    /// `"cg"` (preconditioned conjugate gradients, signed, the walls' pressure the
    /// fluid's mirrored plus its hydrostatic difference: `schemes::dfsph::cg`), one
    /// particle mass only. The CG converges on closed and periodic flows where the
    /// Jacobi diverges (Poiseuille and the heated channel within 1 %), holds a column
    /// within 4 % and the dam break's front as the Jacobi does, but halts the heated
    /// cavity (docs/validation/schemes/CG.md).
    #[serde(default)]
    pub solver: DfsphSolver,
    /// Particle shifting in a closed domain (the CG only; no particle of the scene
    /// held at a free surface at its first step): after each drift every particle
    /// moves by `-D sum_j V_j (1 + R (W_ij / W(dx))^4) grad W_ij` (walls included)
    /// towards where its neighbours are sparser, with `D = shift h v_max dt` (`h`
    /// half the kernel's support, `v_max` the step's largest speed), at most 0.45
    /// `h^2`, and at most a tenth of a spacing: Lind et al. 2012's Fickian shift with
    /// its anti-clustering term, with Sun et al. 2017's coefficient (4, their CFL Ma
    /// (2h)^2) as the default (`schemes::dfsph::cg`). Without it the particles follow
    /// the flow into strained, clustered arrangements whose density noise the
    /// constant-density solve corrects with pressures the flow does not have: the
    /// Taylor-Green vortex decays 57 % too fast (0.45 % with it). 0 turns it off.
    #[serde(default = "default_shift")]
    pub shift: f32,
}

/// The iteration of DFSPH's two solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum DfsphSolver {
    /// B&K's relaxed Jacobi iteration on compression only, Akinci's walls.
    #[default]
    Jacobi,
    /// Preconditioned conjugate gradients on the signed system, mirrored walls.
    Cg,
}

fn default_density_tolerance() -> f32 {
    1e-3
}
fn default_divergence_tolerance() -> f32 {
    1e-3
}
fn default_max_iterations() -> u32 {
    100
}
fn default_shift() -> f32 {
    4.0
}

impl Default for DfsphSettings {
    fn default() -> Self {
        Self {
            density_tolerance: default_density_tolerance(),
            divergence_tolerance: default_divergence_tolerance(),
            max_iterations: default_max_iterations(),
            compact_gradients: false,
            solver: DfsphSolver::Jacobi,
            shift: default_shift(),
        }
    }
}
