//! WCSPH's settings in a scene's `solver` table: `delta_sph` and
//! `transport_velocity` (each absent, off, by default).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// δ-SPH (Molteni & Colagrossi 2009, Comput. Phys. Commun. 180; Antuono et al.
/// 2010, Comput. Phys. Commun. 181): density from the continuity equation,
/// `drho_i/dt = m_i sum_j v_ij . grad W_ij + sum_b psi_b v_i . grad W_ib`, the time
/// derivative of the summation density, plus the diffusion
/// `delta h c sum_j V_j 2 (rho_i - rho_j - rho^H_ij) (x_ij . grad W_ij) / (r^2 + 0.01 h^2)`
/// (a Laplacian of the density; `V_j = m_j / rho_j`, h half the kernel's support)
/// between particles of one material (c that material's own speed of sound,
/// [`EquationOfState::sound_speed`]), with the hydrostatic difference
/// `rho^H_ij = rho0 g . x_ij / c^2` taken out (Fourtakas et al. 2019, Comput. Fluids
/// 190, eq. 12, linearised: exact for the linear equation of state, to order
/// `(v/c)^2` for Tait), so a resting column feels no diffusion. Each particle starts
/// at the density of the weight of the fluid above it (rest density where gravity
/// runs along a periodic axis).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DeltaSph {
    /// Diffusion coefficient delta (dimensionless, 0 to 1; 0.1 is the usual choice).
    #[serde(default = "default_delta")]
    pub delta: f32,
}

fn default_delta() -> f32 {
    0.1
}

/// The transport-velocity formulation of Adami, Hu & Adams (2013, J. Comput. Phys.
/// 241, eqs. 13 and 14): each drift moves a particle with `v + dt/2 a_b`, where `a_b
/// = -p_b / m_i sum_j (V_i^2 + V_j^2) grad W_ij` is the acceleration a uniform
/// background pressure `p_b` would give it, walls included as in the pressure
/// force; its velocity does not take `a_b`. A particle distribution with holes or
/// clumps has a non-zero `a_b` that moves particles into the holes; an even one has
/// none. Meant for closed or periodic domains: at a free surface the missing
/// neighbours make `a_b` pull particles out of the fluid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TransportVelocity {
    /// Background pressure `p_b` (Pa). Adami et al. take `rho0 c^2`; on the
    /// Taylor-Green vortex `2 rho0 c^2` matched the exact decay more closely here
    /// (docs/validation/taylor-green).
    pub background: f32,
}
