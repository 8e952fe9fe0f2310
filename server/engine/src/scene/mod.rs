//! The scene model: one serde definition of everything a scene holds.
//!
//! A scene is written in TOML or JSON (see [`load`]), or taken from a built-in
//! preset ([`presets`]) and adjusted with `key=value` overrides. The JSON Schema
//! printed by `floe schema` is derived from these types, so the schema, the
//! parser and the docs cannot disagree. [`validate`] checks every field once and
//! names the offending one by its path (`fluids[0].rest_density: must be > 0, got -3`).
//!
//! Units are SI throughout: metres, seconds, kilograms, pascals.

pub mod load;
pub mod presets;
pub mod tunable;
pub mod validate;

use crate::kernel::KernelKind;
pub use crate::modules::fluid::spec::{EquationOfState, Fluid, FluidBlock, TaylorGreen, Viscosity};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A complete scene: what is simulated, where, and how.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Human-readable name.
    #[serde(default = "default_name")]
    pub name: String,
    /// Physics modules this scene uses (`floe modules` lists them). The engine builds
    /// only the buffers and passes of the modules listed here.
    #[serde(default = "default_modules")]
    pub modules: Vec<String>,
    /// Distance between neighbouring particles when blocks are filled (m). Sets the
    /// resolution: each particle's mass is its material's rest density over the
    /// kernel sum of a full lattice of this spacing, so a block at rest sums to
    /// exactly its rest density.
    pub particle_spacing: f32,
    /// Gravitational acceleration (m/s^2).
    #[serde(default = "default_gravity")]
    pub gravity: [f32; 3],
    /// Fluid phases (the `fluid` module), each a material of its own.
    #[serde(default)]
    pub fluids: Vec<Fluid>,
    /// Static walls, sampled with boundary particles (Akinci et al. 2012).
    #[serde(default)]
    pub boundaries: Vec<Boundary>,
    /// Simulation domain. Particles that leave it halt the scene. Default: the
    /// bounding box of all fluid blocks and boundaries, grown by one kernel support.
    #[serde(default)]
    pub domain: Option<BoxRegion>,
    /// Axes along which the domain is periodic: what leaves through one face comes
    /// back through the opposite one (minimum-image pairs, see `floe_engine::periodic`).
    /// Needs an explicit `domain` at least two kernel supports long on each such axis,
    /// and walls that are boxes open across it. Fill a periodic axis with whole
    /// particle spacings, or the lattice has a seam there.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub periodic: Vec<Axis>,
    /// Solver settings.
    #[serde(default)]
    pub solver: Solver,
    /// Bounds beyond which the scene halts instead of producing garbage.
    #[serde(default)]
    pub guard: Guard,
    /// Temperature, conduction and buoyancy (the `heat` module).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heat: Option<crate::modules::heat::spec::Heat>,
    /// Non-Newtonian viscosity (the `snow` module).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snow: Option<crate::modules::snow::spec::Snow>,
}

fn default_name() -> String {
    "scene".into()
}
fn default_modules() -> Vec<String> {
    vec!["fluid".into()]
}
fn default_gravity() -> [f32; 3] {
    [0.0, -9.81, 0.0]
}

/// A coordinate axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

impl Axis {
    /// 0, 1, 2 for x, y, z.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }
}

impl Scene {
    /// Which of x, y, z are periodic.
    pub fn periodic_axes(&self) -> [bool; 3] {
        let mut axes = [false; 3];
        for a in &self.periodic {
            axes[a.index()] = true;
        }
        axes
    }
}

/// An axis-aligned box (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxRegion {
    /// Lower corner (m).
    pub min: [f32; 3],
    /// Upper corner (m).
    pub max: [f32; 3],
}

/// A static wall sampled with boundary particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Boundary {
    /// The inside of a box is free; its six faces are walls. `min`/`max` are the
    /// wall surfaces fluid touches; particles sit half a spacing outside them.
    Box {
        /// Lower corner of the free interior (m).
        min: [f32; 3],
        /// Upper corner of the free interior (m).
        max: [f32; 3],
        /// Faces to leave open, from `-x +x -y +y -z +z`.
        #[serde(default)]
        open: Vec<Face>,
        /// Layers of boundary particles (1 to 4).
        #[serde(default = "default_layers")]
        layers: u32,
    },
    /// A rectangle: fluid stays on the side its `normal` points to.
    Plane {
        /// Centre of the rectangle (m).
        center: [f32; 3],
        /// Normal pointing into the fluid (normalised on load).
        normal: [f32; 3],
        /// Edge lengths (m) along two tangents chosen from the normal.
        size: [f32; 2],
        /// Layers of boundary particles (1 to 4).
        #[serde(default = "default_layers")]
        layers: u32,
    },
    /// The ground: a heightfield over `[min, max]` in x and z with Coulomb friction
    /// (`floe_engine::terrain`); fluid stays above it.
    Terrain(crate::terrain::spec::Terrain),
}

pub(crate) fn default_layers() -> u32 {
    1
}

/// A face of a box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Face {
    /// Lower x face.
    #[serde(rename = "-x")]
    MinusX,
    /// Upper x face.
    #[serde(rename = "+x")]
    PlusX,
    /// Lower y face.
    #[serde(rename = "-y")]
    MinusY,
    /// Upper y face.
    #[serde(rename = "+y")]
    PlusY,
    /// Lower z face.
    #[serde(rename = "-z")]
    MinusZ,
    /// Upper z face.
    #[serde(rename = "+z")]
    PlusZ,
}

/// Solver settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Solver {
    /// Pressure solver (the scheme that orders a step).
    #[serde(default)]
    pub method: Method,
    /// Kernel family.
    #[serde(default)]
    pub kernel: KernelKind,
    /// Kernel support radius as a multiple of `particle_spacing`. 2 gives about
    /// 30 neighbours in 3D, the usual choice.
    #[serde(default = "default_support_factor")]
    pub support_factor: f32,
    /// Time integrator.
    #[serde(default)]
    pub integrator: Integrator,
    /// Speed of sound c (m/s). Default: `mach_factor * expected_max_speed`.
    #[serde(default)]
    pub speed_of_sound: Option<f32>,
    /// Ratio c / v_max (10 keeps density fluctuations near 1 %, Monaghan 1994).
    #[serde(default = "default_mach_factor")]
    pub mach_factor: f32,
    /// Expected maximum flow speed (m/s). Default: `sqrt(2 g H)` with H the fluid's
    /// height along gravity, or the fastest initial block velocity, whichever is larger.
    #[serde(default)]
    pub expected_max_speed: Option<f32>,
    /// Time step control.
    #[serde(default)]
    pub time_step: TimeStep,
    /// Velocity damping rate (1/s) applied while `t < damping_until`, to let a
    /// scene settle before it is measured (hydrostatic tests). 0 disables it.
    #[serde(default)]
    pub damping: f32,
    /// Simulated time (s) at which damping stops.
    #[serde(default)]
    pub damping_until: f32,
    /// The DFSPH solves' tolerances and iteration limit (used when `method = "dfsph"`).
    #[serde(default)]
    pub dfsph: DfsphSettings,
    /// Transport-velocity formulation (WCSPH only; none by default): particles drift
    /// with their velocity plus the push of a uniform background pressure, which
    /// keeps them evenly spread where shear would line them up or clump them.
    #[serde(default)]
    pub transport_velocity: Option<TransportVelocity>,
    /// δ-SPH (WCSPH only; none by default): density integrated by the continuity
    /// equation with a density-diffusion term instead of summed from positions, so
    /// the pressure of a disordered or resting fluid is smooth rather than noisy.
    #[serde(default)]
    pub delta_sph: Option<DeltaSph>,
}

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

fn default_support_factor() -> f32 {
    2.0
}
fn default_mach_factor() -> f32 {
    10.0
}

impl Default for Solver {
    fn default() -> Self {
        Self {
            method: Method::default(),
            kernel: KernelKind::default(),
            support_factor: default_support_factor(),
            integrator: Integrator::default(),
            speed_of_sound: None,
            mach_factor: default_mach_factor(),
            expected_max_speed: None,
            time_step: TimeStep::default(),
            damping: 0.0,
            damping_until: 0.0,
            dfsph: DfsphSettings::default(),
            transport_velocity: None,
            delta_sph: None,
        }
    }
}

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

impl Default for DfsphSettings {
    fn default() -> Self {
        Self {
            density_tolerance: default_density_tolerance(),
            divergence_tolerance: default_divergence_tolerance(),
            max_iterations: default_max_iterations(),
        }
    }
}

/// Pressure solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Weakly compressible SPH: pressure from an equation of state, explicit steps
    /// limited by the speed of sound (Monaghan 1994; Becker & Teschner 2007).
    #[default]
    Wcsph,
    /// Divergence-free SPH (Bender & Koschier 2015, 2017): an iterative
    /// divergence-free solve and constant-density solve per step, steps limited by
    /// the flow speed alone (`solver.dfsph` holds the tolerances).
    Dfsph,
}

impl Method {
    /// The override (`--set`, a scene's `overrides`) that picks this scheme.
    pub const fn setting(self) -> &'static str {
        match self {
            Method::Wcsph => "solver.method=\"wcsph\"",
            Method::Dfsph => "solver.method=\"dfsph\"",
        }
    }
}

/// Time integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// Symplectic (semi-implicit) Euler: `v += dt a; x += dt v`.
    #[default]
    SymplecticEuler,
    /// Leap-frog, kick-drift-kick (velocity Verlet), second order.
    Leapfrog,
}

/// How the time step is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "mode", rename_all = "snake_case", deny_unknown_fields)]
pub enum TimeStep {
    /// The largest stable step from the CFL, viscous and force limits
    /// (Monaghan 1992; Morris et al. 1997, eqs. 19-20), clamped to `[min, max]`.
    /// A stable step below `min` halts the scene.
    Adaptive {
        /// CFL number lambda in `dt <= lambda h / (c + v_max)`, h the smoothing
        /// length (half the support). 0.5 with the default support of two spacings
        /// moves sound half a particle spacing per step. With several fluids c is
        /// the fastest `c_a sqrt(rho0_a / rho0_b)`: a light fluid's particles move
        /// against a heavy one's stiffness at its interface.
        #[serde(default = "default_cfl")]
        cfl: f32,
        /// Smallest step allowed (s).
        #[serde(default = "default_dt_min")]
        min: f32,
        /// Largest step allowed (s).
        #[serde(default = "default_dt_max")]
        max: f32,
    },
    /// Advance in intervals of `dt` (s). When `dt` exceeds the stable limit the
    /// interval is cut into equal sub-steps no longer than the limit (counted in the
    /// run's statistics).
    Fixed {
        /// Interval (s).
        dt: f32,
        /// CFL number used for the stable limit.
        #[serde(default = "default_cfl")]
        cfl: f32,
    },
}

fn default_cfl() -> f32 {
    0.5
}
fn default_dt_min() -> f32 {
    1e-7
}
fn default_dt_max() -> f32 {
    5e-3
}

impl Default for TimeStep {
    fn default() -> Self {
        Self::Adaptive { cfl: default_cfl(), min: default_dt_min(), max: default_dt_max() }
    }
}

/// Stability guard bounds: crossing one halts the scene with a reason.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Guard {
    /// Largest compression `(rho - rho0) / rho0` allowed.
    #[serde(default = "default_max_compression")]
    pub max_compression: f32,
    /// Largest particle speed allowed (m/s). Default: the speed of sound, since a
    /// weakly compressible fluid faster than sound is no longer meaningful.
    #[serde(default)]
    pub max_speed: Option<f32>,
}

fn default_max_compression() -> f32 {
    0.5
}

impl Default for Guard {
    fn default() -> Self {
        Self { max_compression: default_max_compression(), max_speed: None }
    }
}

/// The JSON Schema of a scene document, as printed by `floe schema`.
pub fn json_schema() -> serde_json::Value {
    let mut schema = serde_json::to_value(schemars::schema_for!(Scene)).expect("a schema is plain JSON");
    let core = tunable::CORE.iter();
    for t in core.chain(crate::modules::all().iter().flat_map(|m| m.tunables)) {
        tunable::mark(&mut schema, t);
    }
    schema
}
