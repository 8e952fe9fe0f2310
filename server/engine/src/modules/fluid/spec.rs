//! The fluid module's scene section: fluid phases (each a material), their
//! equation of state, viscosity, XSPH, and the blocks they fill.

pub use crate::materials::{EquationOfState, Look};
pub use crate::validation::taylor_green::TaylorGreen;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One fluid phase: its material and where it starts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// Name of the phase.
    #[serde(default = "default_fluid_name")]
    pub name: String,
    /// Rest density rho0 (kg/m^3). Water: 1000.
    #[serde(default = "default_rest_density")]
    pub rest_density: f32,
    /// Equation of state relating density to pressure.
    #[serde(default)]
    pub eos: EquationOfState,
    /// Viscosity model.
    #[serde(default)]
    pub viscosity: Viscosity,
    /// XSPH velocity correction factor epsilon (Monaghan 1989), 0 to 1; 0 disables it.
    #[serde(default)]
    pub xsph: f32,
    /// How viewers draw it: "water" (the default), "snow", "ice" or "solid".
    #[serde(default, skip_serializing_if = "Look::is_water")]
    pub look: Look,
    /// Boxes filled with particles on a cubic lattice of `particle_spacing`. None:
    /// the fluid starts without particles and gets them while the scene runs, which
    /// only a fluid another setting fills may do (the snow a snowfall's cover
    /// releases, `snowfall.release.fluid`; the melt of a fluid that melts like it,
    /// `heat.fluids[i].melting.into`).
    pub blocks: Vec<FluidBlock>,
}

fn default_fluid_name() -> String {
    "water".into()
}
fn default_rest_density() -> f32 {
    1000.0
}

/// A box of fluid particles, or the sphere, cylinder or mesh it bounds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FluidBlock {
    /// Lower corner (m); the first particle centre sits half a spacing inside.
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
    /// The shape within the box the block holds (default: the whole box).
    #[serde(default, skip_serializing_if = "BlockShape::is_box")]
    pub shape: BlockShape,
    /// Initial velocity (m/s).
    #[serde(default)]
    pub velocity: [f32; 3],
    /// Taylor-Green vortices added to `velocity`, for flows that start in motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub taylor_green: Option<TaylorGreen>,
    /// A closed mesh (OBJ or STL) that shapes the block: scaled uniformly and
    /// centred to fit the box `min`-`max`, the block holds the lattice points inside it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<crate::mesh::MeshSource>,
}

impl FluidBlock {
    /// A block at rest between `min` and `max`.
    pub fn at_rest(min: [f32; 3], max: [f32; 3]) -> Self {
        Self { min, max, shape: BlockShape::Box, velocity: [0.0; 3], taylor_green: None, mesh: None }
    }

    /// The initial velocity (m/s) of a particle at `x` (m): `velocity` plus the
    /// vortices, if any.
    pub fn velocity_at(&self, x: [f32; 3]) -> [f32; 3] {
        let [u, v] = self.taylor_green.map_or([0.0; 2], |tg| tg.velocity(x[0] - self.min[0], x[1] - self.min[1]));
        [self.velocity[0] + u, self.velocity[1] + v, self.velocity[2]]
    }
}

/// The shape a block's box bounds: the lattice points of the box inside it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BlockShape {
    /// The whole box.
    #[default]
    Box,
    /// The ellipsoid inscribed in the box (a ball in a cube).
    Sphere,
    /// The elliptic cylinder inscribed in the box along x.
    CylinderX,
    /// The elliptic cylinder inscribed in the box along y.
    CylinderY,
    /// The elliptic cylinder inscribed in the box along z.
    CylinderZ,
}

impl BlockShape {
    /// Whether it is the whole box.
    pub fn is_box(&self) -> bool {
        *self == BlockShape::Box
    }

    /// Whether the point `x` of the box `min`-`max` is inside the shape.
    pub fn holds(self, min: [f32; 3], max: [f32; 3], x: [f32; 3]) -> bool {
        // Each coordinate relative to the box's centre, in half-widths.
        let u: [f32; 3] = std::array::from_fn(|k| (2.0 * x[k] - min[k] - max[k]) / (max[k] - min[k]));
        let across = |skip: usize| (0..3).filter(|&k| k != skip).map(|k| u[k] * u[k]).sum::<f32>() <= 1.0;
        match self {
            BlockShape::Box => true,
            BlockShape::Sphere => u.iter().map(|v| v * v).sum::<f32>() <= 1.0,
            BlockShape::CylinderX => across(0),
            BlockShape::CylinderY => across(1),
            BlockShape::CylinderZ => across(2),
        }
    }
}

/// Viscosity model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Viscosity {
    /// No explicit viscosity.
    None,
    /// Physical viscosity through a kernel Laplacian (Müller et al. 2003, eq. 14;
    /// with the cubic kernel, Morris et al. 1997, eq. 8). Momentum conserving.
    Laplacian {
        /// Kinematic viscosity nu (m^2/s). Water: 1e-6.
        nu: f32,
    },
    /// Monaghan's artificial viscosity (Monaghan 1992, eq. 4.1), acting only on
    /// approaching pairs; `nu_eff ~ alpha c h / 10`, c the fluid's own speed of sound
    /// ([`EquationOfState::sound_speed`]).
    Artificial {
        /// Dimensionless alpha, typically 0.01 to 0.1.
        alpha: f32,
    },
}

impl Default for Viscosity {
    fn default() -> Self {
        Self::Artificial { alpha: 0.02 }
    }
}
