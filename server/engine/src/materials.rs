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
//!
//! **Phases.** A particle may change material while the scene runs (ice melting
//! into water, water freezing): a module declares the material it changes into as
//! a *phase* of the one it changes from ([`crate::model::ModelBuilder::phase`]) and
//! writes the particle's `material` attribute from a pass (on the GPU, the w of its
//! position). The rule that keeps this sound: the phases of one substance share one
//! particle mass (the first phase's, `rho0 / sum_j W` at the particle spacing), so
//! a particle keeps its mass when it changes, and mass is conserved exactly. A phase
//! of another rest density then holds its particles at another number density
//! (water from ice, `m = rho_ice / sum W`, packs 1000/917 times as densely as ice
//! to reach `rho_water`: melting contracts). Everything else follows the particle's
//! material on the next evaluation: its rest density, its equation of state, and
//! each module's per-material settings, which a phase takes from the material it is
//! declared *like* ([`Material::settings`], [`per_material`]).

use crate::math::Real;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Fluid or solid: how the core treats a material's particles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaterialKind {
    /// Moves under pressure and viscosity.
    Fluid,
    /// Held in shape by a solid module (takes part in density and pressure as a fluid does).
    Solid,
}

impl MaterialKind {
    /// `fluid` or `solid`.
    pub const fn name(self) -> &'static str {
        match self {
            MaterialKind::Fluid => "fluid",
            MaterialKind::Solid => "solid",
        }
    }
}

/// How viewers draw a material's particles when no channel colours them. The
/// server sends each material's look with the scene's info; the viewer knows no
/// module.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Look {
    /// Blue and translucent (the surface view renders it as water).
    #[default]
    Water,
    /// White and opaque.
    Snow,
    /// Pale blue-white and translucent.
    Ice,
    /// Grey and opaque.
    Solid,
}

impl Look {
    /// Its name, as scene files and the scene's info spell it.
    pub fn name(self) -> &'static str {
        match self {
            Look::Water => "water",
            Look::Snow => "snow",
            Look::Ice => "ice",
            Look::Solid => "solid",
        }
    }

    /// Whether it is the default (scene files may leave it out).
    pub fn is_water(&self) -> bool {
        *self == Look::Water
    }
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
    /// Its equation of state (a scheme with pressure from density, WCSPH, reads it).
    pub eos: EquationOfState,
    /// How viewers draw it.
    pub look: Look,
    /// Particle mass (kg): `rho0 / sum_j W(x_ij)` over a full cubic lattice of the
    /// particle spacing, so summation gives exactly `rho0` in the initial interior.
    /// (`rho0 spacing^3` would not: poly6 at support 2 spacings sums ~10 % high on a
    /// lattice, and the Tait equation turns that into an explosion.) A phase has
    /// the mass of the material it is a phase of.
    pub mass: Real,
    /// Where its settings stand in the modules' per-material lists (a fluid's
    /// viscosity, `heat.fluids`): the materials with settings of their own are
    /// numbered in order (without phases, this is the material's index); a phase
    /// takes the number of the material it was declared like.
    pub settings: usize,
}

/// A module's per-material values for every material of the table, from `own`, its
/// values for the materials with settings of their own (in their order): a phase
/// takes those of the material it is like.
pub fn per_material<T: Clone>(materials: &[Material], own: &[T]) -> Vec<T> {
    materials.iter().map(|m| own[m.settings].clone()).collect()
}

/// The materials of a scene, indexed by the `material` attribute.
#[derive(Debug, Clone, PartialEq)]
pub struct Materials {
    list: Vec<Material>,
}

impl Materials {
    /// A table of `list` (at most 256 materials: frames send the index as a byte;
    /// none in a scene without SPH particles, e.g. snowfall alone).
    pub fn new(list: Vec<Material>) -> Self {
        assert!(list.len() <= 256, "at most 256 materials");
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

    /// Whether the scene has no materials (no SPH particles).
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
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

/// Equation of state p(rho). Pressure is clamped at zero (no tension), which
/// avoids the tensile instability at free surfaces. A background pressure p_b,
/// added before the clamp, lets a flow without a free surface (closed or periodic)
/// carry pressures below the mean: Morris, Fox & Zhu (1997, J. Comput. Phys. 136,
/// section 2.3) and Adami, Hu & Adams (2013, J. Comput. Phys. 241) use `p_b` of the
/// order of `rho0 c^2` against tensile instability. It does not move the pressure
/// gradient of an exact SPH sum, but it scales the force of any disorder: measured
/// with the default support of 2 spacings, a lattice at rest (c = 10 m/s, rho0 c^2 =
/// 1e5 Pa) stays still under 1e3 Pa and goes unstable under 1e4 Pa. Default 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum EquationOfState {
    /// Tait: `p = B ((rho/rho0)^gamma - 1)`, `B = rho0 c^2 / gamma`
    /// (Monaghan 1994, J. Comput. Phys. 110, eq. 3.4; Becker & Teschner 2007, eq. 7).
    Tait {
        /// Exponent gamma (7 for water).
        #[serde(default = "default_gamma")]
        gamma: f32,
        /// Background pressure p_b (Pa) added before the clamp at zero.
        #[serde(default, skip_serializing_if = "is_zero")]
        background: f32,
    },
    /// Linear "ideal gas" model `p = k (rho - rho0)` (Müller et al. 2003, eq. 12,
    /// with the rest density offset of Desbrun & Gascuel). Default `k = c^2`.
    Linear {
        /// Stiffness k (m^2/s^2 = Pa m^3/kg). Default: the squared speed of sound.
        #[serde(default)]
        stiffness: Option<f32>,
        /// Background pressure p_b (Pa) added before the clamp at zero.
        #[serde(default, skip_serializing_if = "is_zero")]
        background: f32,
    },
}

fn default_gamma() -> f32 {
    7.0
}

fn is_zero(v: &f32) -> bool {
    *v == 0.0
}

impl Default for EquationOfState {
    fn default() -> Self {
        Self::Tait { gamma: default_gamma(), background: 0.0 }
    }
}

impl EquationOfState {
    /// The fluid's own speed of sound (m/s) in a scene whose speed of sound is `c`:
    /// a linear law's stiffness `k` gives `sqrt(k)`, every other law takes `c`
    /// itself (not recomputed from B, whose rounding would move it by an ulp). What
    /// scales with a fluid's sound, its artificial viscosity and its density
    /// diffusion, takes this one: a light fluid made as stiff as a heavy one keeps
    /// the dissipation its own sound calls for (docs/heat.md, two layers at rest).
    pub fn sound_speed(&self, c: f32) -> f32 {
        match *self {
            Self::Linear { stiffness: Some(k), .. } => k.sqrt(),
            _ => c,
        }
    }
}
