//! The snowfall module's scene section (`snowfall`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Snow falling over a rectangle of ground, and what it lands on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Snowfall {
    /// The horizontal rectangle flakes are emitted over and the snow grid covers:
    /// `min` and `max` as `[x, z]` (m). A flake that leaves it sideways has left.
    pub area: Area,
    /// Height flakes are emitted at (m).
    pub height: f32,
    /// Height of the ground where no terrain covers it (m; default 0).
    #[serde(default)]
    pub floor: f32,
    /// How many flakes fall: `light`, `moderate`, `heavy`, `blizzard`
    /// ([`Intensity::flakes_per_m2_s`]) or `{"flakes_per_m2_s": F}`. Live, up to
    /// `max_intensity`.
    #[serde(default)]
    pub intensity: Intensity,
    /// The most the intensity may be set to while the scene runs (default the
    /// intensity): the ring of flakes is sized for it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_intensity: Option<Intensity>,
    /// Depth of snow the fall lays on open flat ground at `max_intensity` (m per
    /// hour; default 0.05, a heavy snowfall). Each flake carries
    /// `depth_per_hour / 3600 / max_intensity` cubic metres of snow: a scene may lay
    /// snow faster than any storm does (a time-lapse) without more flakes, and a
    /// lighter fall set while it runs lays proportionally less.
    #[serde(default = "default_depth_per_hour")]
    pub depth_per_hour: f32,
    /// Speed a flake falls at in still air (m/s; default 1, dry snow's 0.5 to 1.5).
    #[serde(default = "default_terminal_speed")]
    pub terminal_speed: f32,
    /// Mean wind `[x, z]` (m/s). Live.
    #[serde(default)]
    pub wind: [f32; 2],
    /// Gusts: the wind is `wind (1 + gusts sin(2 pi t / gust_period))` (0 to 1). Live.
    #[serde(default)]
    pub gusts: f32,
    /// Period of the gusts (s; default 5).
    #[serde(default = "default_gust_period")]
    pub gust_period: f32,
    /// A wind field from noise added to the mean wind: gusts that vary across the
    /// area as well as in time. Absent: none. Live.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turbulence: Option<Turbulence>,
    /// Flutter: each step a random acceleration, each component uniform in
    /// `[-flutter, flutter]` (m/s^2; default 1). Live.
    #[serde(default = "default_flutter")]
    pub flutter: f32,
    /// Edge of the snow grid's square cells (m; default the particle spacing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cell: Option<f32>,
    /// Objects snow lands on: boxes (a roof, a house, a car) and cylinders (trees).
    #[serde(default)]
    pub objects: Vec<Object>,
    /// Half-angle from the vertical of the directions the coverage samples
    /// (degrees, 0 to 80; default 25; see `coverage`).
    #[serde(default = "default_coverage_cone")]
    pub coverage_cone: f32,
    /// The cover on the slopes released as particles of a fluid (with the `snow`
    /// module, avalanche snow), its mass conserved. Absent: the cover stays.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub release: Option<Release>,
}

/// The release of the snow cover on the slopes (see the module's `release`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Release {
    /// The fluid (its `name` in `fluids`) the cover becomes.
    pub fluid: String,
    /// Scene time of the release (s). Live: setting it to the scene's time, or
    /// earlier, releases after the next step; each value releases once. Absent: no
    /// release until it is set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<f32>,
    /// Ground at least this steep releases its cover (degrees, 0 to 90; default 20).
    #[serde(default = "default_min_slope")]
    pub min_slope: f32,
    /// Particles the releases may create in all: room reserved when the scene is
    /// created, counted by the server's particle limit (default 20,000).
    #[serde(default = "default_release_particles")]
    pub particles: u32,
}

/// Turbulence: smooth value noise in space and time (trilinear between random
/// values on a lattice `scale` metres and `period` seconds apart, smoothstep
/// weights), each horizontal component between `-amplitude` and `amplitude`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Turbulence {
    /// Largest speed it adds to each horizontal component (m/s).
    pub amplitude: f32,
    /// Size of its eddies: the lattice's spacing (m; default 5).
    #[serde(default = "default_turbulence_scale")]
    pub scale: f32,
    /// How long an eddy lasts: the lattice's spacing in time (s; default 4).
    #[serde(default = "default_turbulence_period")]
    pub period: f32,
}

fn default_turbulence_scale() -> f32 {
    5.0
}

fn default_turbulence_period() -> f32 {
    4.0
}

/// A horizontal rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Area {
    /// Lower corner `[x, z]` (m).
    pub min: [f32; 2],
    /// Upper corner `[x, z]` (m).
    pub max: [f32; 2],
}

/// How many flakes fall per square metre and second.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", untagged)]
pub enum Intensity {
    /// A named intensity.
    Named(Named),
    /// Flakes per square metre per second.
    Rate {
        /// Flakes per m^2 per s.
        flakes_per_m2_s: f32,
    },
}

/// The named intensities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Named {
    /// 20 flakes per m^2 per s.
    Light,
    /// 50.
    Moderate,
    /// 100.
    Heavy,
    /// 200.
    Blizzard,
}

impl Default for Intensity {
    fn default() -> Self {
        Intensity::Named(Named::Heavy)
    }
}

impl Snowfall {
    /// The most flakes per m^2 per s the scene may be set to.
    pub fn max_flakes_per_m2_s(&self) -> f32 {
        self.max_intensity.unwrap_or(self.intensity).flakes_per_m2_s()
    }
}

impl Intensity {
    /// Flakes per square metre per second. Each simulated flake stands for many
    /// (its snow is `depth_per_hour`'s): the named rates are for the eye.
    pub fn flakes_per_m2_s(self) -> f32 {
        match self {
            Intensity::Named(Named::Light) => 20.0,
            Intensity::Named(Named::Moderate) => 50.0,
            Intensity::Named(Named::Heavy) => 100.0,
            Intensity::Named(Named::Blizzard) => 200.0,
            Intensity::Rate { flakes_per_m2_s } => flakes_per_m2_s,
        }
    }
}

/// Something snow lands on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Object {
    /// An axis-aligned box (m): a roof on its own is a thin one off the ground.
    Box {
        /// Lower corner.
        min: [f32; 3],
        /// Upper corner.
        max: [f32; 3],
    },
    /// An upright cylinder (m): a tree.
    Cylinder {
        /// Centre of its footprint `[x, z]`.
        centre: [f32; 2],
        /// Radius.
        radius: f32,
        /// Height of its bottom.
        bottom: f32,
        /// Height of its top.
        top: f32,
    },
    /// A closed mesh (OBJ or STL: an asset of the server's `--assets` or inline),
    /// scaled uniformly and centred to fit the box `min`-`max` (m), as a fluid
    /// block's mesh fits its box; as fine as the snow grid (a column per cell).
    Mesh {
        /// The mesh.
        mesh: crate::mesh::MeshSource,
        /// Lower corner of its box (m).
        min: [f32; 3],
        /// Upper corner.
        max: [f32; 3],
    },
}

fn default_depth_per_hour() -> f32 {
    0.05
}

fn default_terminal_speed() -> f32 {
    1.0
}

fn default_gust_period() -> f32 {
    5.0
}

fn default_flutter() -> f32 {
    1.0
}

fn default_min_slope() -> f32 {
    20.0
}

fn default_release_particles() -> u32 {
    20_000
}

fn default_coverage_cone() -> f32 {
    25.0
}
