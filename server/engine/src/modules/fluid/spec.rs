//! The fluid module's scene section: fluid phases (each a material), their
//! equation of state, viscosity, XSPH, and the blocks they fill.

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
    /// Boxes filled with particles on a cubic lattice of `particle_spacing`.
    pub blocks: Vec<FluidBlock>,
}

fn default_fluid_name() -> String {
    "water".into()
}
fn default_rest_density() -> f32 {
    1000.0
}

/// A box of fluid particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FluidBlock {
    /// Lower corner (m); the first particle centre sits half a spacing inside.
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
    /// Initial velocity (m/s).
    #[serde(default)]
    pub velocity: [f32; 3],
    /// Taylor-Green vortices added to `velocity`, for flows that start in motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub taylor_green: Option<TaylorGreen>,
}

impl FluidBlock {
    /// A block at rest between `min` and `max`.
    pub fn at_rest(min: [f32; 3], max: [f32; 3]) -> Self {
        Self { min, max, velocity: [0.0; 3], taylor_green: None }
    }

    /// The initial velocity (m/s) of a particle at `x` (m): `velocity` plus the
    /// vortices, if any.
    pub fn velocity_at(&self, x: [f32; 3]) -> [f32; 3] {
        let [u, v] = self.taylor_green.map_or([0.0; 2], |tg| tg.velocity(x[0] - self.min[0], x[1] - self.min[1]));
        [self.velocity[0] + u, self.velocity[1] + v, self.velocity[2]]
    }
}

/// The Taylor-Green vortex field in the x-y plane (Taylor & Green 1937; the 2D
/// solution of VALIDATION.md §4): `u = -U cos(2 pi x / L) sin(2 pi y / L)`,
/// `v = U sin(2 pi x / L) cos(2 pi y / L)`, x and y from the block's lower corner.
/// It is divergence free and, in a periodic box of side L, decays as `exp(-8 pi^2
/// nu t / L^2)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TaylorGreen {
    /// Peak speed U (m/s).
    pub amplitude: f32,
    /// Wavelength L (m): the side of one period of four vortices.
    pub wavelength: f32,
}

impl TaylorGreen {
    /// `(u, v)` (m/s) at `(x, y)` (m) from the field's origin.
    pub fn velocity(&self, x: f32, y: f32) -> [f32; 2] {
        let k = std::f32::consts::TAU / self.wavelength;
        let (sx, cx) = (k * x).sin_cos();
        let (sy, cy) = (k * y).sin_cos();
        [-self.amplitude * cx * sy, self.amplitude * sx * cy]
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

/// The integration of the per-particle viscous force ([`super::varying`]), chosen
/// by the module whose viscosity varies (`snow.solver`, `heat.viscous_solver`).
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
