//! The snowfall module: flakes emitted over an area, drifting in the wind, landing
//! on objects, on the ground and on the snow already there, and the snow cover
//! they build, as in the snow thesis's snowfall half (its eqs. 2.5-2.6; see
//! [`flakes`] for the motion and what Floe adds to it).
//!
//! - Flakes live in a space of their own (`flakes`), a ring of slots: flake number
//!   `f` is born into slot `f mod capacity` and the capacity is sized so that no
//!   flake is still airborne when its slot comes round again (a flake older than
//!   [`SnowfallConsts::max_age`] has left). So births and landings need no
//!   compaction on either backend, and the accounting is exact: emitted = airborne
//!   + landed + left, in integers ([`flakes::tally`]).
//! - The snow cover is a grid of square cells over the area (`snow_cells`): each
//!   cell counts the flakes landed on the ground (`ground_count`) and on the tops of
//!   objects (`top_count`); each flake is `depth_per_flake` metres of snow over a
//!   cell, so depth grows with time, sheltered cells get none, and the next flakes
//!   land on the snow (`snow_surface`, refreshed each step before they move).
//! - Streams: the `flakes` set (positions, every slot: landed flakes stay where
//!   they landed until their slot is reused) and the `snow_cover` grid with
//!   `snow_depth` and `top_depth` (m).
//!
//! - The thesis's coverage (eqs. 2.1-2.2, [`coverage`]): a grid channel of how
//!   much of each cell's ground is exposed to the sky, computed once at build.
//!
//! - The cover on the slopes may be released as particles of a fluid, mass
//!   conserved ([`release`]): snowfall, then an avalanche.
//!
//! - Objects: boxes and cylinders (exact), and meshes as columns over the
//!   grid's cells ([`columns`]).

pub mod accounts;
pub mod cases;
pub mod columns;
pub mod cover;
pub mod coverage;
pub mod cpu;
pub mod flakes;
pub mod presets;
pub mod release;
pub mod spec;
mod validate;

use crate::attrs::{AttrSpec, Column, Elem, Role};
use crate::channels::SetSpec;
use crate::materials::Look;
use crate::math::{Real, Vec3};
use crate::model::{BuildError, Model, ModelBuilder};
use crate::module::{BenchCase, BenchKind, BenchSize, ModuleDef, Section};
use crate::plan::{PassSpec, Stage};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
pub use accounts::Accounts;
use spec::Object;

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "snowfall",
    about: "Snowfall: flakes in the wind that land on the ground and on objects and build a snow cover.",
    requires: &[],
    section: Some(Section { def: SectionDef::of::<spec::Snowfall>(SECTION), missing: Some("is required") }),
    validate: validate::validate,
    count,
    materials: |_| 0,
    claims: |_| Vec::new(),
    particles: |_, _| Ok(()),
    build,
    retune,
    tunables: TUNABLES,
    cpu: &[("snowfall.emit", &cpu::Emit), ("snowfall.fall", &cpu::Fall), ("snowfall.surface", &cpu::Surface)],
    presets: presets::PRESETS,
    dt_limit,
    measures: accounts::measures,
    cases: cases::CASES,
    stability: cases::STABILITY,
    bench: &[BenchCase {
        name: "snowfall",
        about: "Flakes stepped per second: the snow_roof scene with an intensity that keeps about --particles flakes in the air (4 m of fall at 1 m/s over 64 m^2)",
        kind: BenchKind::Run {
            preset: "snow_roof",
            measures: &["snowfall.airborne", "snowfall.landed", "snowfall.left"],
            size: BenchSize::Space(FLAKES, airborne),
        },
    }],
};

/// `snow_roof`'s intensity for about `n` flakes in the air: a flake falls 4 m at
/// 1 m/s over 64 m^2 of area, so `n / 256` per m^2 per s, with flutter.
fn airborne(n: usize) -> Vec<String> {
    let flux = n as f64 / 256.0;
    vec![format!("snowfall.intensity={{\"flakes_per_m2_s\":{flux}}}"), "snowfall.flutter=1".into()]
}

/// The module's section of a scene.
pub const SECTION: &str = "snowfall";

/// The flakes' space and set.
pub const FLAKES: &str = "flakes";
/// The counters' space (four counters).
pub const COUNTERS: &str = "snowfall";
/// The snow grid's cells, and its set.
pub const CELLS: &str = "snow_cells";
/// The snow grid's set.
pub const COVER: &str = "snow_cover";

/// [`OBJECT_TOP`] where no object stands over a cell's centre.
pub const NO_OBJECT: f32 = f32::MIN;

/// Objects a scene may hold (the GPU's uniform has room for this many).
pub const MAX_OBJECTS: usize = 16;

/// Cells the snow grid may have.
pub const MAX_CELLS: u64 = 1 << 22;

/// The scene's section (the registry builds the module only for scenes with one).
pub fn section(scene: &Scene) -> spec::Snowfall {
    scene.section(SECTION).expect("the registry builds snowfall only for scenes with its section")
}

/// The module's live settings.
pub const TUNABLES: &[Tunable] = &[
    Tunable {
        path: "snowfall.wind",
        unit: "m/s",
        min: None,
        max: None,
        about: "Mean wind [x, z].",
        module: "snowfall",
    },
    Tunable {
        path: "snowfall.intensity",
        unit: "",
        min: None,
        max: None,
        about: "Flakes per m^2 per s (a name or {\"flakes_per_m2_s\": F}), up to max_intensity.",
        module: "snowfall",
    },
    Tunable {
        path: "snowfall.gusts",
        unit: "",
        min: Some(0.0),
        max: Some(1.0),
        about: "Relative amplitude of the gusts.",
        module: "snowfall",
    },
    Tunable {
        path: "snowfall.turbulence",
        unit: "",
        min: None,
        max: None,
        about: "Wind from noise: {\"amplitude\": m/s, \"scale\": m, \"period\": s}, or null for none.",
        module: "snowfall",
    },
    Tunable {
        path: "snowfall.flutter",
        unit: "m/s^2",
        min: Some(0.0),
        max: None,
        about: "Amplitude of the flakes' random flutter.",
        module: "snowfall",
    },
    Tunable {
        path: "snowfall.release.at",
        unit: "s",
        min: Some(0.0),
        max: None,
        about: "When the cover on the slopes is released (the scene's time or earlier: after the next step).",
        module: "snowfall",
    },
];

const fn attr(name: &'static str, elem: Elem, unit: &'static str, role: Role, space: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role, added_later: false, space, module: "snowfall", about: name }
}

/// Flake positions (m).
pub static FLAKE_X: AttrSpec = attr("flake_x", Elem::Vec3, "m", Role::State, FLAKES);
/// Flake velocities (m/s), and in w the flake's state ([`flakes::AIRBORNE`], ...; 0 a
/// slot never used).
pub static FLAKE_V: AttrSpec = attr("flake_v", Elem::Vec4, "m/s", Role::State, FLAKES);
/// Flake ages (s).
pub static FLAKE_AGE: AttrSpec = attr("flake_age", Elem::F32, "s", Role::State, FLAKES);
/// The counters ([`flakes::tally`]).
pub static TALLY: AttrSpec = attr("snowfall_tally", Elem::U32, "", Role::State, COUNTERS);
/// The emission's carry and the clock ([`flakes::timer`]).
pub static TIMER: AttrSpec = attr("snowfall_timer", Elem::F32, "", Role::State, COUNTERS);
/// Flakes landed on the ground in each cell.
pub static GROUND_COUNT: AttrSpec = attr("ground_count", Elem::U32, "", Role::State, CELLS);
/// Flakes landed on objects' tops in each cell.
pub static TOP_COUNT: AttrSpec = attr("top_count", Elem::U32, "", Role::State, CELLS);
/// Height of the ground under each cell's centre (m): a terrain's, else the floor.
pub static BED: AttrSpec = attr("snow_bed", Elem::F32, "m", Role::Constant, CELLS);
/// Height of the top of the object over each cell's centre (m; [`NO_OBJECT`]
/// where there is none): where the viewer draws the snow on objects.
pub static OBJECT_TOP: AttrSpec = attr("object_top", Elem::F32, "m", Role::Constant, CELLS);
/// The thesis's coverage of each cell's ground (0 to 1, [`coverage`]).
pub static COVERAGE: AttrSpec = attr("coverage", Elem::F32, "", Role::Constant, CELLS);
/// The coverage of the top of the object over each cell (0 to 1; 0 where none).
pub static TOP_COVERAGE: AttrSpec = attr("top_coverage", Elem::F32, "", Role::Constant, CELLS);
/// Per cell: the height of the snow's surface on the ground, the snow's depth on
/// objects' tops, and the bottom and top of the meshes' column (m): what a flake
/// lands on, in one element.
pub static SURFACE: AttrSpec = attr("snow_surface", Elem::Vec4, "m", Role::Derived, CELLS);

const fn post_step(
    name: &'static str,
    reads: &'static [&'static str],
    writes: &'static [&'static str],
    accumulates: &'static [&'static str],
) -> PassSpec {
    PassSpec { name, module: "snowfall", stage: Stage::PostStep, reads, writes, accumulates, tolerance: 0.0 }
}

/// The step's births: counts them, advancing the tally and the clock.
pub static EMIT: PassSpec = post_step("snowfall.emit", &[], &["snowfall_timer"], &["snowfall_tally"]);
/// Moves the flakes, lands them, and adds the born.
pub static FALL: PassSpec = PassSpec {
    tolerance: 1e-4,
    ..post_step(
        "snowfall.fall",
        &["snowfall_timer", "snow_surface"],
        &["flake_x", "flake_v", "flake_age"],
        &["snowfall_tally", "ground_count", "top_count"],
    )
};
/// The surface flakes land on, from the counts (before the flakes move).
pub static SURFACE_PASS: PassSpec = PassSpec {
    name: "snowfall.surface",
    module: "snowfall",
    stage: Stage::Kick,
    reads: &["ground_count", "top_count", "snow_bed", "snow_columns"],
    writes: &["snow_surface"],
    accumulates: &[],
    tolerance: 1e-6,
};

/// The module's constants (the GPU's `snowfall` uniform holds the same).
#[derive(Debug, Clone)]
pub struct SnowfallConsts {
    /// The area's corners `[x, z]` (m): the snow grid's.
    pub area_min: [f32; 2],
    /// Its upper corner.
    pub area_max: [f32; 2],
    /// Where flakes are born `[x, z]` (m): the area moved upwind by the distance the
    /// mean wind carries a flake while it falls to the floor, `W (height - floor) / v_t`,
    /// so that a steady wind brings the whole flux onto the area.
    pub emit_min: [f32; 2],
    /// Its upper corner.
    pub emit_max: [f32; 2],
    /// The floor (m): a flake at or below it outside the area has left.
    pub floor: f32,
    /// Emission height (m).
    pub height: f32,
    /// Flakes emitted per second over the whole area.
    pub rate: f32,
    /// Terminal speed (m/s).
    pub terminal_speed: f32,
    /// Drag's relaxation time `v_t / |g|` (s).
    pub tau: f32,
    /// Mean wind `[x, z]` (m/s).
    pub wind: [f32; 2],
    /// Relative amplitude of the gusts.
    pub gusts: f32,
    /// `2 pi / gust_period` (1/s).
    pub gust_omega: f32,
    /// Flutter amplitude (m/s^2).
    pub flutter: f32,
    /// The turbulence: amplitude (m/s), `1 / scale` (1/m), `1 / period` (1/s);
    /// all 0 without it ([`flakes::turbulence`]).
    pub turbulence: [f32; 3],
    /// A flake still airborne at this age (s) has left: `3 (height - floor) / v_t + 1`.
    pub max_age: f32,
    /// Snow depth one flake adds to a cell (m).
    pub depth_per_flake: f32,
    /// Slots in the ring of flakes.
    pub capacity: u32,
    /// The grid's corner `[x, z]` (m): the area's.
    pub origin: [f32; 2],
    /// Cell edge (m).
    pub cell: f32,
    /// Cells along x.
    pub nx: u32,
    /// Cells along z.
    pub nz: u32,
    /// The boxes and cylinders, two vec4 each: a box `(min, 0), (max, 0)`; a
    /// cylinder `(cx, bottom, cz, 1), (radius, top, 0, 0)`. (Meshes are columns
    /// over the cells, [`columns`].)
    pub objects: Vec<[[f32; 4]; 2]>,
    /// The release of the cover, if the scene has one (set at build).
    pub release: Option<release::ReleaseConsts>,
}

impl SnowfallConsts {
    fn new(scene: &Scene) -> Self {
        let s = section(scene);
        let g = Vec3::from(scene.gravity).length();
        let (nx, nz) = cells(&s, scene.particle_spacing);
        let area = (s.area.max[0] - s.area.min[0]) * (s.area.max[1] - s.area.min[1]);
        let flux = s.intensity.flakes_per_m2_s();
        let max_age = max_age(&s);
        let cell = cell_of(&s, scene.particle_spacing);
        let drift = s.wind.map(|w| -w * (s.height - s.floor) / s.terminal_speed);
        Self {
            area_min: s.area.min,
            area_max: s.area.max,
            emit_min: [s.area.min[0] + drift[0], s.area.min[1] + drift[1]],
            emit_max: [s.area.max[0] + drift[0], s.area.max[1] + drift[1]],
            floor: s.floor,
            height: s.height,
            rate: flux * area,
            terminal_speed: s.terminal_speed,
            tau: s.terminal_speed / g,
            wind: s.wind,
            gusts: s.gusts,
            gust_omega: std::f32::consts::TAU / s.gust_period,
            flutter: s.flutter,
            turbulence: s.turbulence.map_or([0.0; 3], |t| [t.amplitude, 1.0 / t.scale, 1.0 / t.period]),
            max_age,
            depth_per_flake: s.depth_per_hour / 3600.0 / s.max_flakes_per_m2_s() / (cell * cell),
            capacity: capacity(&s, scene.particle_spacing, g) as u32,
            origin: s.area.min,
            cell,
            nx,
            nz,
            objects: s.objects.iter().filter_map(pack).collect(),
            release: None,
        }
    }

    /// The snow grid as a grid set's geometry.
    pub fn grid(&self) -> floe_proto::GridInfo {
        floe_proto::GridInfo {
            origin: [self.origin[0], 0.0, self.origin[1]],
            size: [self.cell * self.nx as f32, 0.0, self.cell * self.nz as f32],
            dims: [self.nx, 1, self.nz],
        }
    }
}

/// A box's or a cylinder's two vec4 (a mesh is none).
fn pack(o: &Object) -> Option<[[f32; 4]; 2]> {
    match *o {
        Object::Box { min, max } => Some([[min[0], min[1], min[2], 0.0], [max[0], max[1], max[2], 0.0]]),
        Object::Cylinder { centre, radius, bottom, top } => {
            Some([[centre[0], bottom, centre[1], 1.0], [radius, top, 0.0, 0.0]])
        }
        Object::Mesh { .. } => None,
    }
}

fn cell_of(s: &spec::Snowfall, spacing: f32) -> f32 {
    s.cell.unwrap_or(spacing)
}

/// Cells along x and z.
fn cells(s: &spec::Snowfall, spacing: f32) -> (u32, u32) {
    let cell = cell_of(s, spacing);
    let n = |axis: usize| (((s.area.max[axis] - s.area.min[axis]) / cell).ceil() as u32).max(1);
    (n(0), n(1))
}

fn max_age(s: &spec::Snowfall) -> f32 {
    3.0 * (s.height - s.floor) / s.terminal_speed + 1.0
}

/// The fastest a flake moves (m/s): the wind at its gusts' peak plus the
/// turbulence's largest, the fall, and what the flutter adds within a drag time
/// `tau` (s).
fn fastest(wind: [f32; 2], gusts: f32, turbulence: f32, terminal_speed: f32, flutter: f32, tau: f32) -> f32 {
    wind[0].hypot(wind[1]) * (1.0 + gusts) + turbulence * std::f32::consts::SQRT_2 + terminal_speed + flutter * tau
}

/// The longest step the module allows (s): a flake moves at most half a cell.
fn step_limit(cell: f32, fastest: f32) -> f32 {
    (0.5 * cell / fastest).min(0.5)
}

/// Slots the ring needs: every flake born while the oldest can still be airborne,
/// and two steps' more, under gravity `g` (m/s^2).
fn capacity(s: &spec::Snowfall, spacing: f32, g: f32) -> u64 {
    let area = f64::from((s.area.max[0] - s.area.min[0]) * (s.area.max[1] - s.area.min[1]));
    let rate = f64::from(s.max_flakes_per_m2_s()) * area;
    let turbulence = s.turbulence.map_or(0.0, |t| t.amplitude);
    let speed = fastest(s.wind, s.gusts, turbulence, s.terminal_speed, s.flutter, s.terminal_speed / g);
    let span = f64::from(max_age(s)) + 2.0 * f64::from(step_limit(cell_of(s, spacing), speed));
    (rate * span).ceil() as u64 + 2
}

/// The ring of flakes, the four counters and the grid's cells.
fn count(scene: &Scene) -> Vec<(&'static str, u64)> {
    // (Called while the scene is validated: a missing section is reported there.)
    let Some(s) = scene.section::<spec::Snowfall>(SECTION) else { return Vec::new() };
    let (nx, nz) = cells(&s, scene.particle_spacing);
    let g = Vec3::from(scene.gravity).length();
    let mut out =
        vec![(FLAKES, capacity(&s, scene.particle_spacing, g)), (COUNTERS, 4), (CELLS, u64::from(nx) * u64::from(nz))];
    out.extend(s.release.iter().flat_map(release::count));
    out
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let s = section(scene);
    let mut c = SnowfallConsts::new(scene);
    let n = c.capacity as usize;
    b.space(FLAKES, n);
    b.zeros(&FLAKE_X);
    b.zeros(&FLAKE_V);
    b.zeros(&FLAKE_AGE);
    b.space(COUNTERS, 4);
    b.zeros(&TALLY);
    b.zeros(&TIMER);
    let cells = (c.nx * c.nz) as usize;
    b.space(CELLS, cells);
    let bed = (0..cells)
        .map(|k| {
            let (x, z) = flakes::centre(&c, k);
            b.ground_at(x, z).unwrap_or(s.floor)
        })
        .collect::<Vec<f32>>();
    let mut meshes = Vec::new();
    for (i, o) in s.objects.iter().enumerate() {
        if let Object::Mesh { mesh, min, max } = o {
            let loaded = mesh.load().map_err(|e| BuildError::Mesh(format!("snowfall.objects[{i}].mesh: {e}")))?;
            meshes.push(loaded.fitted(crate::math::Aabb::new((*min).into(), (*max).into())));
        }
    }
    let columns = columns::columns(&c, &meshes);
    let tops: Vec<f32> = (0..cells)
        .map(|k| {
            let (x, z) = flakes::centre(&c, k);
            let boxes = flakes::object_top(&c, f32::MAX, Vec3::new(x, f32::MIN, z), 0.0);
            boxes.unwrap_or(NO_OBJECT).max(columns[k][1])
        })
        .collect();
    b.attr(&COVERAGE, Column::F32(coverage::coverage(&c, &bed, &columns, s.coverage_cone)));
    b.attr(&TOP_COVERAGE, Column::F32(coverage::top_coverage(&c, &bed, &columns, &tops, s.coverage_cone)));
    b.attr(&OBJECT_TOP, Column::F32(tops));
    b.attr(&columns::COLUMNS, Column::Vec4(columns));
    if let Some(r) = &s.release {
        c.release = Some(release::build(r, &c, &bed, b)?);
    }
    b.attr(&BED, Column::F32(bed));
    b.zeros(&GROUND_COUNT);
    b.zeros(&TOP_COUNT);
    b.zeros(&SURFACE);
    b.pass(&EMIT);
    b.pass(&FALL);
    b.pass(&SURFACE_PASS);
    b.set(SetSpec { look: Some(Look::Snow), ..SetSpec::points(FLAKES, FLAKES, "flake_x") });
    cover::declare(b, c.grid());
    b.set_consts(c);
    Ok(())
}

/// Intensity (up to the maximum the ring was sized for), wind, gusts,
/// turbulence, flutter and the release's time may change (the ring keeps its size, the release its
/// cells).
fn retune(scene: &Scene, model: &mut Model) {
    let old = model.consts::<SnowfallConsts>();
    let at = section(scene).release.and_then(|r| r.at);
    let release = old.release.clone().map(|r| release::ReleaseConsts { at, ..r });
    model.set_consts(SnowfallConsts { capacity: old.capacity, release, ..SnowfallConsts::new(scene) });
}

fn dt_limit(model: &Model) -> Option<(&'static str, Real)> {
    let c = model.consts::<SnowfallConsts>();
    let speed = fastest(c.wind, c.gusts, c.turbulence[0], c.terminal_speed, c.flutter, c.tau);
    Some(("snowfall", step_limit(c.cell, speed)))
}

#[cfg(test)]
mod tests;
