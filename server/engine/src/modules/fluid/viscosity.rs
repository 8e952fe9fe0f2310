//! Viscosity: the pairwise terms of the two models a scene can choose.
//!
//! Both are written as accelerations on particle i from neighbour j and are
//! antisymmetric in (i, j) for equal masses, so they conserve linear momentum.

use crate::kernel::Kernel;
use crate::math::{Real, Vec3};

/// A viscosity model with its constants resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViscosityModel {
    /// No explicit viscosity.
    None,
    /// Laplacian viscosity with dynamic viscosity `mu = nu rho0` (Pa s):
    /// `a_i = mu / rho_i sum_j m_j / rho_j (v_j - v_i) L(r_ij)` (Müller et al. 2003, eq. 14).
    Laplacian {
        /// Dynamic viscosity mu (Pa s).
        mu: Real,
    },
    /// Monaghan (1992, eq. 4.1): `Pi_ij = -alpha c h mu_ij / rho_ij` for approaching
    /// pairs, `mu_ij = v_ij . x_ij / (|x_ij|^2 + 0.01 h^2)`, h the smoothing
    /// length (half the support); `a_i = -sum_j m_j Pi_ij grad W_ij`.
    Artificial {
        /// `alpha c h` (m^2/s), precomputed.
        alpha_c_h: Real,
        /// `0.01 h^2` (m^2), the singularity guard.
        eps_h2: Real,
    },
}

impl ViscosityModel {
    /// Resolves a scene's viscosity for rest density `rho0` (kg/m^3), speed of sound
    /// `c` (m/s), the scene's kernel and particle spacing (m). The Laplacian's
    /// viscosity carries the kernel's lattice normalisation
    /// ([`Kernel::lattice_laplacian_scale`]): without it the steady Poiseuille
    /// profile stalls about 1 % slow however fine the particles.
    pub fn new(spec: super::spec::Viscosity, rho0: Real, c: Real, kernel: &Kernel, spacing: Real) -> Self {
        use super::spec::Viscosity;
        let h = 0.5 * kernel.support();
        match spec {
            Viscosity::None => ViscosityModel::None,
            Viscosity::Laplacian { nu } => ViscosityModel::Laplacian {
                mu: nu * rho0 * kernel.lattice_laplacian_scale(spacing, |r| kernel.laplacian(r)),
            },
            Viscosity::Artificial { alpha } => {
                ViscosityModel::Artificial { alpha_c_h: alpha * c * h, eps_h2: 0.01 * h * h }
            }
        }
    }

    /// Acceleration on i from neighbour j (or from a wall particle with `v_j = 0`,
    /// `m_j` its pseudo-mass and `rho_j = rho0`). `x_ij = x_i - x_j`, `r = |x_ij|`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn pair(
        &self,
        kernel: &Kernel,
        x_ij: Vec3,
        r: Real,
        v_ij: Vec3,
        m_j: Real,
        rho_i: Real,
        rho_j: Real,
        grad: Vec3,
    ) -> Vec3 {
        match *self {
            ViscosityModel::None => Vec3::ZERO,
            ViscosityModel::Laplacian { mu } => -v_ij * (mu * m_j / (rho_i * rho_j) * kernel.laplacian(r)),
            ViscosityModel::Artificial { alpha_c_h, eps_h2 } => {
                // Receding pairs (v_ij . x_ij >= 0) get mu_ij = 0, without a branch:
                // approaching and receding neighbours are equally likely.
                let mu_ij = v_ij.dot(x_ij).min(0.0) / (r * r + eps_h2);
                let pi_ij = -alpha_c_h * mu_ij * 2.0 / (rho_i + rho_j);
                -grad * (m_j * pi_ij)
            }
        }
    }

    /// Acceleration on i from wall particle b (pseudo-mass `psi_b`, density `rho0`).
    /// Laplacian viscosity sees the wall as the mirror image of i (velocity `-v_i`,
    /// Morris, Fox & Zhu 1997, with the fluid and wall particles at equal distance
    /// from the wall surface), so the fluid is at rest on the wall surface rather
    /// than half a spacing behind it, at the wall particles; artificial viscosity sees
    /// the wall at rest.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn wall(
        &self,
        kernel: &Kernel,
        x_ib: Vec3,
        r: Real,
        v_i: Vec3,
        psi_b: Real,
        rho_i: Real,
        rho0: Real,
        grad: Vec3,
    ) -> Vec3 {
        let v_ib = if let ViscosityModel::Laplacian { .. } = self { v_i * 2.0 } else { v_i };
        self.pair(kernel, x_ib, r, v_ib, psi_b, rho_i, rho0, grad)
    }

    /// The model acting between particles of two different materials: the harmonic
    /// mean of two Laplacian viscosities (the interface flux of Cleary 1998, as in
    /// Morris et al. 1997 for variable viscosity), otherwise the larger artificial
    /// viscosity of the two, or the one model present.
    pub fn mix(&self, other: &ViscosityModel) -> ViscosityModel {
        use ViscosityModel::*;
        match (*self, *other) {
            (Laplacian { mu: a }, Laplacian { mu: b }) => {
                Laplacian { mu: if a + b > 0.0 { 2.0 * a * b / (a + b) } else { 0.0 } }
            }
            (Artificial { alpha_c_h: a, eps_h2 }, Artificial { alpha_c_h: b, .. }) => {
                Artificial { alpha_c_h: a.max(b), eps_h2 }
            }
            (m @ Artificial { .. }, _) | (_, m @ Artificial { .. }) => m,
            (None, m) | (m, None) => m,
        }
    }

    /// The kinematic viscosity this model acts like (m^2/s), for the viscous
    /// time-step limit: Laplacian `mu / rho0`; artificial `alpha c h / 10`
    /// (Monaghan 2005, Rep. Prog. Phys. 68, eq. 4.16 with the 3D factor 1/10).
    pub fn effective_nu(&self, rho0: Real) -> Real {
        match *self {
            ViscosityModel::None => 0.0,
            ViscosityModel::Laplacian { mu } => mu / rho0,
            ViscosityModel::Artificial { alpha_c_h, .. } => alpha_c_h / 10.0,
        }
    }
}
