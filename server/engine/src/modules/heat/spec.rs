//! The heat module's scene section (`heat`): each fluid's thermal properties,
//! where the fluid starts hotter or colder, which walls hold a fixed temperature,
//! and volumetric heat sources. Temperatures are absolute (K).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Temperature, conduction and Boussinesq buoyancy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Heat {
    /// Thermal properties of each fluid, in the order of `fluids` (one entry each).
    pub fluids: Vec<ThermalFluid>,
    /// Reference temperature T0 of the Boussinesq buoyancy (K): a particle at T0
    /// feels plain gravity.
    #[serde(default = "default_reference")]
    pub reference_temperature: f32,
    /// The acceleration buoyancy acts along (m/s^2); default: the scene's gravity.
    /// In a closed container full of fluid, give the scene no gravity and this one
    /// g: the pressure then carries only its departure from hydrostatic balance
    /// (the Boussinesq reduced pressure), and the SPH error of a hydrostatic
    /// pressure gradient, several per cent of g, no longer drowns the buoyancy
    /// (docs/heat.md). With a free surface keep the scene's gravity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub buoyancy_gravity: Option<[f32; 3]>,
    /// Boxes whose particles start at their own temperature instead of their
    /// fluid's; a particle in several takes the last one's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<TemperatureBox>,
    /// Wall particles inside these boxes are held at the box's temperature
    /// (Dirichlet); a wall particle in several takes the first one's. Every other
    /// wall is insulated (no heat crosses it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub walls: Vec<TemperatureBox>,
    /// Volumetric heat sources: particles inside a box gain its power density.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sources: Vec<HeatSource>,
    /// Heat fluxes through the surfaces of boxes (walls'): the heat enters the
    /// fluid within one particle spacing of the box. Such a wall is otherwise
    /// insulated unless it is also in `walls`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fluxes: Vec<WallFlux>,
    /// Smallest and largest temperature the scene may reach (K); a particle outside
    /// halts the scene, naming it.
    #[serde(default = "default_range")]
    pub range: [f32; 2],
}

/// A fluid's thermal properties.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ThermalFluid {
    /// Thermal conductivity k (W/(m K)). Water: 0.6.
    pub conductivity: f32,
    /// Specific heat capacity c (J/(kg K)). Water: 4186.
    pub heat_capacity: f32,
    /// Volumetric thermal expansion coefficient beta (1/K) of the Boussinesq
    /// buoyancy `g (1 - beta (T - T0))`. Water near 20 °C: 2.1e-4; 0 switches it off.
    #[serde(default)]
    pub expansion: f32,
    /// Initial temperature (K).
    #[serde(default = "default_reference")]
    pub temperature: f32,
}

/// A box and a temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TemperatureBox {
    /// Lower corner (m).
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
    /// Temperature (K).
    pub temperature: f32,
}

/// A volumetric heat source.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HeatSource {
    /// Lower corner (m).
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
    /// Power per volume (W/m^3); negative removes heat.
    pub power: f32,
}

/// A heat flux through the surface of a box, such as a wall's: each particle within
/// one particle spacing `d` outside the box gains `flux d^2` watts (the wall area it
/// covers on the particle lattice), so a layer of fluid on a face of area A takes
/// `flux A` watts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallFlux {
    /// Lower corner (m).
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
    /// Heat flux into the fluid across the box's surface (W/m^2); negative cools.
    pub flux: f32,
}

fn default_reference() -> f32 {
    293.15
}

fn default_range() -> [f32; 2] {
    [1.0, 1e4]
}
