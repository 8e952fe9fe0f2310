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
pub mod sections;
pub mod tunable;
pub mod validate;

use crate::kernel::KernelKind;
use schemars::JsonSchema;
pub use sections::Sections;
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
    /// The modules' sections (`fluids`, `heat`, ...), each owned, parsed and
    /// validated by its module ([`sections`]).
    #[serde(flatten, skip_deserializing)]
    #[schemars(skip)]
    pub sections: Sections,
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
    /// wall surfaces fluid touches; particles sit half a spacing outside them. Along
    /// each axis the wall particles are spaced to fit the extent exactly: make it a
    /// whole number of `particle_spacing` so that they stay level with the fluid's
    /// layers (a 1.0 m wall at 0.0375 m drifts a third of a spacing against 24 layers,
    /// which held DFSPH's resting column 4-5 % above hydrostatic).
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
    /// Pressure solver: the scheme that orders a step (`floe schemes` lists them).
    #[serde(default = "default_method")]
    pub method: String,
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
    /// The schemes' settings (`dfsph`, `delta_sph`, ...), each owned, parsed and
    /// validated by its scheme ([`sections`]).
    #[serde(flatten, skip_deserializing)]
    #[schemars(skip)]
    pub schemes: Sections,
}

fn default_method() -> String {
    crate::registry::SCHEMES[0].id.into()
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
            method: default_method(),
            kernel: KernelKind::default(),
            support_factor: default_support_factor(),
            integrator: Integrator::default(),
            speed_of_sound: None,
            mach_factor: default_mach_factor(),
            expected_max_speed: None,
            time_step: TimeStep::default(),
            damping: 0.0,
            damping_until: 0.0,
            schemes: Sections::default(),
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

/// The core's fields of a scene document (and of its `solver` table): the keys the
/// derived deserialisers take; every other key is a module's or a scheme's section.
const CORE_KEYS: &[&str] =
    &["name", "modules", "particle_spacing", "gravity", "boundaries", "domain", "periodic", "solver", "guard"];
const SOLVER_KEYS: &[&str] = &[
    "method",
    "kernel",
    "support_factor",
    "integrator",
    "speed_of_sound",
    "mach_factor",
    "expected_max_speed",
    "time_step",
    "damping",
    "damping_until",
];

impl Scene {
    /// Reads a scene document: the core's fields, each module's section (parsed by
    /// the module that owns its key) and each scheme's settings under `solver`; a
    /// bad or unknown field is named by its path. Not yet validated
    /// ([`load::from_value`] validates).
    pub fn from_json(value: serde_json::Value) -> Result<Scene, load::SceneError> {
        let serde_json::Value::Object(top) = value else {
            return Err(load::SceneError::Field { path: "scene".into(), message: "must be a table".into() });
        };
        let (mut core, sections) = sections::split(top, "", CORE_KEYS, &crate::module::sections())?;
        let solver_sections = match core.remove("solver") {
            Some(serde_json::Value::Object(solver)) => {
                let (rest, schemes) = sections::split(solver, "solver", SOLVER_KEYS, &crate::scheme::settings())?;
                core.insert("solver".into(), serde_json::Value::Object(rest));
                schemes
            }
            Some(other) => {
                core.insert("solver".into(), other);
                Sections::default()
            }
            None => sections::split(Default::default(), "solver", SOLVER_KEYS, &crate::scheme::settings())?.1,
        };
        let mut scene: Scene = serde_path_to_error::deserialize(serde_json::Value::Object(core)).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." { "scene".into() } else { path };
            load::SceneError::Field { path, message: e.into_inner().to_string() }
        })?;
        scene.sections = sections;
        scene.solver.schemes = solver_sections;
        Ok(scene)
    }

    /// The section `key` of a module, as a `T`.
    pub fn section<T: serde::de::DeserializeOwned>(&self, key: &str) -> Option<T> {
        self.sections.get(key)
    }

    /// This scene with the field at `path` (as in overrides: `fluids[0].xsph`,
    /// `heat`) set to `value`, read again (not validated): how presets build on one
    /// another and set other modules' sections without knowing their types.
    pub fn with(self, path: &str, value: serde_json::Value) -> Scene {
        let mut doc = serde_json::to_value(&self).expect("scenes serialise");
        load::set(&mut doc, path, value).unwrap_or_else(|e| panic!("{path}: {e}"));
        Scene::from_json(doc).unwrap_or_else(|e| panic!("{path}: {e}"))
    }
}

impl Solver {
    /// A scheme's settings `key`, as a `T` (every scheme's settings have their
    /// defaults filled in when a scene is read).
    pub fn settings<T: serde::de::DeserializeOwned>(&self, key: &str) -> Option<T> {
        self.schemes.get(key)
    }

    /// These settings with a scheme's settings `key` set to `value` (a preset's).
    pub fn with(mut self, key: &str, value: serde_json::Value) -> Solver {
        self.schemes.set(key, &value);
        self
    }
}

/// The JSON Schema of a scene document, as printed by `floe schema`: the core's
/// fields, each module's section and each scheme's settings under `solver`.
pub fn json_schema() -> serde_json::Value {
    let mut generator = schemars::SchemaGenerator::default();
    let mut schemas = |defs: Vec<sections::SectionDef>| -> Vec<(&'static str, serde_json::Value)> {
        defs.iter().map(|d| (d.key, (d.schema)(&mut generator).to_value())).collect()
    };
    let (modules, schemes) = (schemas(crate::module::sections()), schemas(crate::scheme::settings()));
    // The root last: it takes every definition the sections' schemas made.
    let mut schema = generator.root_schema_for::<Scene>().to_value();
    sections::add_schemas(&mut schema["properties"], modules);
    sections::add_schemas(&mut schema["$defs"]["Solver"]["properties"], schemes);
    let core = tunable::CORE.iter();
    for t in core.chain(crate::module::all().iter().flat_map(|m| m.tunables)) {
        tunable::mark(&mut schema, t);
    }
    schema
}
