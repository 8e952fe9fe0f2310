//! The snow module's scene section (`snow`): the rheology of each fluid, for
//! non-Newtonian flows such as snow avalanches, and the viscosity clamp.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::viscosity::{ViscousSolver, WallShear};

/// Non-Newtonian viscosity per fluid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Snow {
    /// The rheology of each fluid, in the order of `fluids` (one entry each). It adds
    /// to the fluid's own `viscosity` model, which snow scenes usually set to none.
    pub fluids: Vec<Rheology>,
    /// Largest dynamic viscosity any particle takes (Pa s): the clamp that keeps
    /// power laws and regularised yield stresses finite where the flow is at rest,
    /// and with it the explicit viscous time-step limit `0.125 h^2 rho0 / mu`.
    #[serde(default = "default_max_viscosity")]
    pub max_viscosity: f32,
    /// How walls (boxes, planes, terrain) act on the viscous stress: `no_slip`
    /// (the fluid at rest on the wall surface, as between the plates of a channel)
    /// or `slip` (no shear from walls: an avalanche slides on its bed, held back by
    /// the terrain's Coulomb friction instead).
    #[serde(default)]
    pub walls: WallShear,
    /// How the viscous force advances: `implicit` (the default: backward Euler,
    /// solved by conjugate gradients after each kick, no viscous limit on dt) or
    /// `explicit` (a force, with the explicit viscous time-step limit).
    #[serde(default)]
    pub solver: ViscousSolver,
}

/// A generalised Newtonian fluid: dynamic viscosity as a function of the shear rate
/// `g = sqrt(2 D:D)` (1/s), D the strain-rate tensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Rheology {
    /// No viscosity from this module (a Newtonian fluid keeps its own model).
    None,
    /// Constant viscosity `mu` (Pa s), through the stress-tensor path.
    Newtonian {
        /// Dynamic viscosity (Pa s).
        mu: f32,
    },
    /// Cross (1965): `mu = mu_inf + (mu_0 - mu_inf) / (1 + (K g)^n)`.
    Cross {
        /// Zero-shear viscosity (Pa s).
        mu_0: f32,
        /// Infinite-shear viscosity (Pa s).
        mu_inf: f32,
        /// Time constant K (s).
        k: f32,
        /// Rate exponent n (dimensionless).
        n: f32,
    },
    /// Power law (Ostwald-de Waele): `mu = K g^(n-1)`.
    PowerLaw {
        /// Consistency K (Pa s^n).
        k: f32,
        /// Flow index n: below 1 shear-thinning, above 1 thickening.
        n: f32,
    },
    /// Bingham plastic, regularised after Papanastasiou (1987, J. Rheol. 31, eq. 6):
    /// `mu = mu_p + tau_0 (1 - exp(-m g)) / g`.
    Bingham {
        /// Yield stress tau_0 (Pa).
        yield_stress: f32,
        /// Plastic viscosity mu_p (Pa s).
        mu_p: f32,
        /// Regularisation time m (s): larger is closer to the ideal plastic.
        #[serde(default = "default_regularisation")]
        m: f32,
    },
    /// Herschel-Bulkley, regularised as Bingham:
    /// `mu = K g^(n-1) + tau_0 (1 - exp(-m g)) / g`.
    HerschelBulkley {
        /// Yield stress tau_0 (Pa).
        yield_stress: f32,
        /// Consistency K (Pa s^n).
        k: f32,
        /// Flow index n.
        n: f32,
        /// Regularisation time m (s).
        #[serde(default = "default_regularisation")]
        m: f32,
    },
    /// Carreau (1972): `mu = mu_inf + (mu_0 - mu_inf) (1 + (lambda g)^2)^((n-1)/2)`.
    Carreau {
        /// Zero-shear viscosity (Pa s).
        mu_0: f32,
        /// Infinite-shear viscosity (Pa s).
        mu_inf: f32,
        /// Relaxation time lambda (s).
        lambda: f32,
        /// Flow index n.
        n: f32,
    },
}

fn default_max_viscosity() -> f32 {
    1e3
}

fn default_regularisation() -> f32 {
    100.0
}
