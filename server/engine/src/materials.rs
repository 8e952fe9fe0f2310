//! The material table: what each particle is made of.
//!
//! Every particle carries the index of its material (the `material` attribute on
//! the CPU when a scene has more than one; on the GPU in the w component of its
//! position, where it costs no binding). The core reads rest density and particle
//! mass from the table; modules keep their own per-material constants (equation of
//! state, viscosity, conductivity) indexed the same way.
//!
//! Several materials follow Solenthaler & Pajarola (2008, "Density contrast SPH
//! interfaces", SCA, eqs. 4-6): density from the particle's own mass and the number
//! density, `rho_i = m_i sum_j W_ij`, so a light particle next to a heavy one is not
//! counted as heavy; the pressure force from `p_i / delta_i^2 + p_j / delta_j^2`
//! with `delta = rho / m`. For equal masses both reduce to the single-material
//! formulas, with the same arithmetic (`crate::cpu` shows how), so a one-material
//! scene computes exactly what it did before materials existed.

use crate::math::Real;

/// Fluid or solid: how the core treats a material's particles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaterialKind {
    /// Moves under pressure and viscosity.
    Fluid,
    /// Held in shape by a solid module (takes part in density and pressure as a fluid does).
    Solid,
}

/// One material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name (the fluid's or solid's name in the scene).
    pub name: String,
    /// Fluid or solid.
    pub kind: MaterialKind,
    /// Rest density rho0 (kg/m^3).
    pub rest_density: Real,
    /// Particle mass (kg): `rho0 / sum_j W(x_ij)` over a full cubic lattice of the
    /// particle spacing, so summation gives exactly `rho0` in the initial interior.
    /// (`rho0 spacing^3` would not: poly6 at support 2 spacings sums ~10 % high on a
    /// lattice, and the Tait equation turns that into an explosion.)
    pub mass: Real,
}

/// The materials of a scene, indexed by the `material` attribute.
#[derive(Debug, Clone, PartialEq)]
pub struct Materials {
    list: Vec<Material>,
}

impl Materials {
    /// A table of `list` (at most 256 materials: frames send the index as a byte).
    pub fn new(list: Vec<Material>) -> Self {
        assert!(!list.is_empty() && list.len() <= 256, "1 to 256 materials");
        Self { list }
    }

    /// Material `i`.
    pub fn get(&self, i: usize) -> &Material {
        &self.list[i]
    }

    /// Number of materials.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether there is only one (then no per-particle index is stored on the CPU).
    pub fn single(&self) -> bool {
        self.list.len() == 1
    }

    /// Never true: a table has at least one material.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Every material, in index order.
    pub fn iter(&self) -> impl Iterator<Item = &Material> {
        self.list.iter()
    }

    /// Every material, in index order, as a slice.
    pub fn as_slice(&self) -> &[Material] {
        &self.list
    }

    /// The largest ratio of rest densities, for reports and stability checks.
    pub fn density_ratio(&self) -> Real {
        let (lo, hi) = self
            .list
            .iter()
            .fold((Real::INFINITY, 0.0 as Real), |(lo, hi), m| (lo.min(m.rest_density), hi.max(m.rest_density)));
        hi / lo
    }
}
