//! The heat module's scene section (`heat`): each fluid's thermal properties,
//! where the fluid starts hotter or colder, which walls hold a fixed temperature,
//! and volumetric heat sources. Temperatures are absolute (K).

use crate::viscosity::ViscousSolver;
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
    /// Largest viscosity (Pa s) a fluid's temperature law gives (the clamp that keeps
    /// an Arrhenius law finite far below its reference temperature, and with it the
    /// explicit viscous time-step limit `0.125 h^2 rho0 / mu`).
    #[serde(default = "default_max_viscosity")]
    pub max_viscosity: f32,
    /// How the temperature laws' viscous force advances: `implicit` (the default:
    /// backward Euler by conjugate gradients, no viscous limit on dt) or `explicit`.
    #[serde(default)]
    pub viscous_solver: ViscousSolver,
}

/// A fluid's thermal properties.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
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
    /// Dynamic viscosity as a function of temperature, in place of the fluid's own
    /// `viscosity` model (which must then be `{"model": "none"}`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscosity: Option<ViscosityLaw>,
    /// A solid that melts: the fluid is the solid phase (ice), with its melting
    /// point and latent heat, and names the fluid its melt becomes (water).
    /// Absent: the fluid never changes phase.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub melting: Option<Melting>,
}

/// Melting and freezing by enthalpy (Floe's model, docs/ice.md): a particle's
/// specific enthalpy rises with the heat it takes in; below the melting point it
/// sets the temperature with this fluid's heat capacity, across the latent heat
/// the temperature stays at the melting point while the liquid fraction rises
/// from 0 to 1, above it the temperature rises with the melt's heat capacity.
/// A fully melted particle becomes a particle of the melt, one that loses its
/// latent heat again becomes the solid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Melting {
    /// Melting point T_m (K). Ice: 273.15.
    #[serde(default = "default_melting_point")]
    pub temperature: f32,
    /// Specific latent heat of fusion L (J/kg). Ice: 3.34e5.
    pub latent_heat: f32,
    /// The fluid (`name`) whose rest density, viscosity and thermal properties the
    /// melt takes, keeping this fluid's particle mass (a phase of it: mass is
    /// conserved exactly). It may start with no blocks.
    pub into: String,
}

/// A fluid's dynamic viscosity as a function of its temperature T (K).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum ViscosityLaw {
    /// Reynolds (1886, Phil. Trans. R. Soc. 177, the exponential law):
    /// `mu = mu_ref exp(-b (T - T_ref))`. Oils and melts over a moderate range.
    Exponential {
        /// Viscosity at the reference temperature (Pa s).
        mu_ref: f32,
        /// Reference temperature (K).
        t_ref: f32,
        /// Temperature coefficient b (1/K): positive thins with heat.
        b: f32,
    },
    /// Arrhenius (Andrade 1930, Nature 125): `mu = mu_ref exp(E/R (1/T - 1/T_ref))`.
    /// Water between 0 and 100 °C: about 1.0e-3 Pa s at 293.15 K with
    /// E/R of about 1900 K.
    Arrhenius {
        /// Viscosity at the reference temperature (Pa s).
        mu_ref: f32,
        /// Reference temperature (K).
        t_ref: f32,
        /// Activation temperature E/R (K): the activation energy over the gas constant.
        activation_temperature: f32,
    },
    /// Measured values: `[T (K), mu (Pa s)]` points in rising temperature, 2 to 8 of
    /// them, linear between points and constant beyond the first and the last.
    Table {
        /// The points.
        points: Vec<[f32; 2]>,
    },
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

fn default_melting_point() -> f32 {
    273.15
}

fn default_max_viscosity() -> f32 {
    1e3
}

fn default_range() -> [f32; 2] {
    [1.0, 1e4]
}
