//! A module that exists only in the tests, to show that a module is additive: it
//! adds attributes, passes, channels and a particle set of its own through the
//! engine's registry, and its channels stream to clients, without an edit to any
//! file outside this folder but the one line that registers it.
//!
//! - `age` (s), per particle: the time since the scene started, advanced by the
//!   pass `tracer.age` in the kick stage (`age += dt`), guarded to stay within
//!   [0, 1000] s.
//! - `spin`, per particle, a rotation (quaternion, state) turning about y at 1 rad/s,
//!   and `frame`, its 3x3 matrix (derived), both written by `tracer.spin` in the
//!   kick stage: the element types a solid's orientation needs, through snapshots
//!   and channels (`spin`; a 3x3 matrix has more components than a frame carries).
//! - `probes`, a second particle set of four points on the domain's diagonal, with
//!   `probe_age` (s): the mean age of the particles, written by `tracer.probe` after
//!   each step.
//! - `tracer_groups`, an index map (in scenes whose particles are never born nor
//!   die): sixteen groups of particles, each particle in
//!   two (`id % 8` and `8 + (id / 8) % 8`). After each step `group_x_sum` is each
//!   group's sum of its live members' positions (m) and `group_sums` each
//!   particle's sum of its groups' sums: a gather, a segmented sum, a spread and a
//!   member sum, the core's generic map passes.
//! - `tracer.floor`, a position solve: no particle below the lowest initial
//!   particle (`floor`, m); an iteration projects the particles of colour `id % 4`
//!   in the sweep of that colour, so one iteration of four sweeps converges (a
//!   broken sweep index never would); the residual is the deepest particle's depth
//!   below the floor (`tracer_depth`, m). On WCSPH it runs after each drift, so no
//!   particle ends a step below the floor; on DFSPH before the density solve
//!   (`position_solve::When`), which the floor, a wall the pressure solve does not
//!   see, then fights: the tests that need the floor at each step's end run WCSPH.
//!
//! - `columns`, a grid of 8 x 1 x 8 cells over the domain's floor, with
//!   `column_count`: the particles above each cell after each step, streamed as
//!   grid frames.
//!
//! - `tracer.raise_ground`, in scenes with a terrain: the core's `ground_height` rises
//!   at `RISE` (m/s) everywhere, a ground that grows under the particles.
//!
//! - Births and deaths, where the scene has a `tracer` section: `births` particles
//!   born after every step at the first of the scene's initial positions, at rest,
//!   or a `body` from a mesh (an asset or inline) born whole after every step;
//!   particles older than `lifetime` (s) removed (`tracer.expire` marks them).
//! - A phase change, where the section has a `phase_age`: the tracer declares
//!   `aged`, a phase of the first fluid with [`PHASE_DENSITY`] times its rest
//!   density, and particles older than `phase_age` (s) change into it
//!   (`tracer.phase` writes their material).
//!
//! Its CPU passes are in `cpu.rs`; its GPU half (`gpu.rs`) is registered as the
//! module is, from outside floe-gpu.

use floe_engine::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use floe_engine::channels::{ChannelSpec, SetSpec, Source};
use floe_engine::guard::Bound;
use floe_engine::maps::MapSpec;
use floe_engine::maps::cpu::{Gather, MemberSum, SegmentSum, Spread};
use floe_engine::math::Vec3;
use floe_engine::model::{BuildError, ModelBuilder};
use floe_engine::module::ModuleDef;
use floe_engine::module::Section;
use floe_engine::plan::{PassSpec, Stage};
use floe_engine::population::{Births, Emitter};
use floe_engine::scene::Scene;
use floe_engine::scene::sections::SectionDef;
use floe_engine::scheme::{Iterate, Op, ReduceOp, Reduction};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

mod cpu;
pub mod gpu;

use cpu::{Age, Columns, Expire, FloorDepth, FloorProject, Phase, Probe, RaiseGround, Spin};

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "tracer",
    about: "Particle ages and probes (a module of the tests).",
    requires: &["fluid"],
    section: Some(Section { def: SectionDef::of::<TracerSpec>("tracer"), missing: None }),
    validate,
    count: |scene| vec![(PROBES, 4), (PARTICLES, u64::from(spec(scene).room(scene.particle_spacing)))],
    materials: |_| 0,
    claims: |_| Vec::new(),
    particles,
    build,
    retune: |_, _| {},
    tunables: &[],
    cpu: &[
        ("tracer.age", &Age),
        ("tracer.spin", &Spin),
        ("tracer.probe", &Probe),
        ("tracer.group_x", &Gather::<Vec3>::new(&GROUPS, "x", "tracer_groups_x")),
        ("tracer.group_sum", &SegmentSum::<Vec3>::new(&GROUPS, "tracer_groups_x", "group_x_sum")),
        ("tracer.group_spread", &Spread::<Vec3>::new(&GROUPS, "group_x_sum", "tracer_groups_sum")),
        ("tracer.member_sum", &MemberSum::<Vec3>::new(&GROUPS, "tracer_groups_sum", "group_sums")),
        ("tracer.floor_project", &FloorProject),
        ("tracer.floor_depth", &FloorDepth),
        ("tracer.columns", &Columns),
        ("tracer.raise_ground", &RaiseGround),
        ("tracer.expire", &Expire),
        ("tracer.phase", &Phase),
    ],
    presets: &[],
    dt_limit: |_| None,
    measures: |_| Vec::new(),
    cases: &[],
    stability: &[],
    bench: &[],
};

/// The tracer's scene section (optional): births and deaths.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TracerSpec {
    /// Particles born after every step, at rest at the first of the scene's initial
    /// positions (0: none).
    #[serde(default)]
    pub births: u32,
    /// Particles older than this (s) are removed after each step (absent: none).
    #[serde(default)]
    pub lifetime: Option<f32>,
    /// Room for this many particles beyond the initial ones (default: ten steps' births).
    #[serde(default)]
    pub reserve: Option<u32>,
    /// A body born whole after every step, at rest, in place of `births` (absent: none).
    #[serde(default)]
    pub body: Option<Body>,
    /// Particles older than this (s) change into the phase `aged` (absent: none).
    #[serde(default)]
    pub phase_age: Option<f32>,
}

/// A body of particles filling a mesh.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// The mesh (an asset of the server's `--assets` directory, or inline).
    pub mesh: floe_engine::mesh::MeshSource,
    /// The box the mesh is fitted into (m).
    pub min: [f32; 3],
    /// Its far corner (m).
    pub max: [f32; 3],
}

impl TracerSpec {
    /// Particles born after every step, at most (a body's lattice box bounds its fill).
    fn per_step(&self, spacing: f32) -> u32 {
        match &self.body {
            Some(b) => floe_engine::sampling::box_count(b.min, b.max, spacing).min(u64::from(u32::MAX)) as u32,
            None => self.births,
        }
    }

    /// Room reserved for particles beyond the initial ones.
    fn room(&self, spacing: f32) -> u32 {
        let per_step = self.per_step(spacing);
        if per_step > 0 { self.reserve.unwrap_or(10 * per_step) } else { 0 }
    }
}

fn spec(scene: &Scene) -> TracerSpec {
    scene.section("tracer").unwrap_or_default()
}

fn validate(scene: &Scene, c: &mut floe_engine::scene::validate::Checker) {
    let s = spec(scene);
    if let Some(l) = s.lifetime {
        c.within("tracer.lifetime", l, 0.0, 1e3);
    }
    if let Some(a) = s.phase_age {
        c.within("tracer.phase_age", a, 0.0, 1e3);
    }
    if let Some(b) = &s.body {
        c.ordered_box("tracer.body", b.min, b.max);
        floe_engine::mesh::validate(c, "tracer.body.mesh", &b.mesh);
    }
}

/// The rest density of the phase `aged`, relative to the first fluid's.
pub const PHASE_DENSITY: f32 = 0.9;

/// The phase's name.
pub const AGED: &str = "aged";

/// Declares the phase `aged` where the scene has a phase age.
fn particles(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    if spec(scene).phase_age.is_some() {
        let rho0 = b.materials()[0].rest_density;
        b.phase(0, 0, AGED, PHASE_DENSITY * rho0);
    }
    Ok(())
}

/// The probes' space.
const PROBES: &str = "probes";

static AGE: AttrSpec = AttrSpec {
    name: "age",
    elem: Elem::F32,
    unit: "s",
    role: Role::State,
    added_later: false,
    space: PARTICLES,
    module: "tracer",
    about: "Time since the scene started.",
};

static SPIN: AttrSpec = AttrSpec {
    name: "spin",
    elem: Elem::Quat,
    unit: "",
    role: Role::State,
    added_later: false,
    space: PARTICLES,
    module: "tracer",
    about: "Orientation, turning about y at 1 rad/s.",
};

static FRAME: AttrSpec = AttrSpec {
    name: "frame",
    elem: Elem::Mat3,
    unit: "",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "tracer",
    about: "The orientation as a rotation matrix.",
};

static PROBE_X: AttrSpec = AttrSpec {
    name: "probe_x",
    elem: Elem::Vec3,
    unit: "m",
    role: Role::Constant,
    added_later: false,
    space: PROBES,
    module: "tracer",
    about: "Probe position.",
};

static PROBE_AGE: AttrSpec = AttrSpec {
    name: "probe_age",
    elem: Elem::F32,
    unit: "s",
    role: Role::Derived,
    added_later: false,
    space: PROBES,
    module: "tracer",
    about: "Mean particle age.",
};

static AGE_PASS: PassSpec = PassSpec {
    name: "tracer.age",
    module: "tracer",
    stage: Stage::Kick,
    reads: &[],
    writes: &[],
    accumulates: &["age"],
    tolerance: 0.0,
};

static SPIN_PASS: PassSpec = PassSpec {
    name: "tracer.spin",
    module: "tracer",
    stage: Stage::Kick,
    reads: &["spin"],
    writes: &["spin", "frame"],
    accumulates: &[],
    tolerance: 1e-5,
};

static PROBE_PASS: PassSpec = PassSpec {
    name: "tracer.probe",
    module: "tracer",
    stage: Stage::PostStep,
    reads: &["age"],
    writes: &["probe_age"],
    accumulates: &[],
    tolerance: 1e-5,
};

/// The groups: particles by id.
pub static GROUPS: MapSpec =
    floe_engine::index_map!("tracer_groups", segments: "groups", members: PARTICLES, module: "tracer");

/// Groups (the map's segments).
pub const GROUP_COUNT: usize = 16;

/// The two groups of particle `id`.
pub fn groups_of(id: u32) -> [usize; 2] {
    [(id % 8) as usize, 8 + ((id / 8) % 8) as usize]
}

/// The columns' space and set.
pub const COLUMNS: &str = "columns";
/// Cells of the columns' grid along x and z.
pub const COLUMN_CELLS: u32 = 8;

static COLUMN_COUNT: AttrSpec = derived("column_count", Elem::F32, "", COLUMNS);
static COLUMNS_PASS: PassSpec = post_step("tracer.columns", &["x"], &["column_count"]);

/// The cell of the columns' grid `grid` above which position `p` is, if any.
pub fn column_of(grid: &floe_proto::GridInfo, p: Vec3) -> Option<usize> {
    let cell = |axis: usize, at: f32| {
        let k = ((at - grid.origin[axis]) / grid.size[axis] * grid.dims[axis] as f32).floor();
        (k >= 0.0 && k < grid.dims[axis] as f32).then_some(k as usize)
    };
    Some(cell(0, p.x)? + grid.dims[0] as usize * cell(2, p.z)?)
}

/// How fast the ground rises in scenes with a terrain (m/s).
pub const RISE: f32 = 0.2;

static RAISE_GROUND: PassSpec = PassSpec {
    name: "tracer.raise_ground",
    module: "tracer",
    stage: Stage::Kick,
    reads: &[],
    writes: &[],
    accumulates: &["ground_height"],
    tolerance: 0.0,
};

static EXPIRE: PassSpec = PassSpec {
    name: "tracer.expire",
    module: "tracer",
    stage: Stage::PostStep,
    reads: &["age"],
    writes: &[],
    accumulates: &["remove"],
    tolerance: 0.0,
};

static PHASE: PassSpec = PassSpec {
    name: "tracer.phase",
    module: "tracer",
    stage: Stage::PostStep,
    reads: &["age"],
    writes: &["material"],
    accumulates: &[],
    tolerance: 0.0,
};

/// The births of every step: at rest at the first initial positions.
fn emit(b: &mut dyn floe_engine::backend::Backend, _: u64, _: f64, _: f32) -> Result<Births, String> {
    let at = &b.model().consts::<TracerConsts>().births;
    Ok(Births { x: at.clone(), v: vec![Vec3::ZERO; at.len()], material: vec![0; at.len()] })
}

/// Colours of the floor solve (its sweeps).
pub const COLOURS: u32 = 4;

const fn derived(name: &'static str, elem: Elem, unit: &'static str, space: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role: Role::Derived, added_later: false, space, module: "tracer", about: name }
}

static GROUP_X: AttrSpec = derived("tracer_groups_x", Elem::Vec3, "m", "tracer_groups");
static GROUP_X_SUM: AttrSpec = derived("group_x_sum", Elem::Vec3, "m", "groups");
static GROUP_SUM_SPREAD: AttrSpec = derived("tracer_groups_sum", Elem::Vec3, "m", "tracer_groups");
static GROUP_SUMS: AttrSpec = derived("group_sums", Elem::Vec3, "m", PARTICLES);
static DEPTH: AttrSpec = derived("tracer_depth", Elem::F32, "m", PARTICLES);

const fn post_step(name: &'static str, reads: &'static [&'static str], writes: &'static [&'static str]) -> PassSpec {
    PassSpec { name, module: "tracer", stage: Stage::PostStep, reads, writes, accumulates: &[], tolerance: 0.0 }
}

static GROUP_X_PASS: PassSpec =
    post_step("tracer.group_x", &["tracer_groups_member", "slot_of", "x"], &["tracer_groups_x"]);
static GROUP_SUM_PASS: PassSpec = post_step(
    "tracer.group_sum",
    &["tracer_groups_start", "tracer_groups_len", "tracer_groups_live", "tracer_groups_x"],
    &["group_x_sum"],
);
static GROUP_SPREAD_PASS: PassSpec =
    post_step("tracer.group_spread", &["tracer_groups_segment", "group_x_sum"], &["tracer_groups_sum"]);
static MEMBER_SUM_PASS: PassSpec = post_step(
    "tracer.member_sum",
    &[
        "tracer_groups_first",
        "tracer_groups_count",
        "tracer_groups_order",
        "tracer_groups_live",
        "id",
        "tracer_groups_sum",
    ],
    &["group_sums"],
);
static FLOOR_PROJECT: PassSpec = PassSpec::solve("tracer", "tracer.floor_project", &["id"], &["x"], &[]);
static FLOOR_DEPTH: PassSpec = PassSpec::solve("tracer", "tracer.floor_depth", &["x"], &["tracer_depth"], &[]);

/// The floor solve.
pub const FLOOR_SOLVE: Iterate = Iterate {
    name: "tracer.floor",
    start: &[Op::Pass("tracer.floor_depth")],
    iteration: &[Op::Pass("tracer.floor_project"), Op::Pass("tracer.floor_depth")],
    residual: Reduction { attr: "tracer_depth", op: ReduceOp::Max },
    tolerance: 0.0,
    min: 0,
    max: 8,
    check_every: 1,
    sweeps: COLOURS,
    max_sweeps: COLOURS,
};

/// The tracer's constants.
#[derive(Debug, Clone)]
pub struct TracerConsts {
    /// Height of the floor (m): the lowest initial particle's.
    pub floor: f32,
    /// The columns' grid.
    pub columns: floe_proto::GridInfo,
    /// Where particles are born, each step (m).
    pub births: Vec<Vec3>,
    /// Particles older than this (s) are removed (infinite: none).
    pub lifetime: f32,
    /// Particles older than this (s) change into the phase `aged` (infinite: none).
    pub phase_age: f32,
    /// The material index of the phase `aged` (0 where there is none).
    pub aged: u32,
}

fn build(_: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    b.zeros(&AGE);
    b.zeros(&SPIN);
    b.zeros(&FRAME);
    b.bound(Bound { attr: "age", what: "age", unit: "s", min: 0.0, max: 1e3 });
    b.space(PROBES, 4);
    let probes = (0..4).map(|k| Vec3::splat(0.1 * k as f32)).collect();
    b.attr(&PROBE_X, Column::Vec3(probes));
    b.zeros(&PROBE_AGE);
    b.pass(&AGE_PASS);
    b.pass(&SPIN_PASS);
    b.pass(&PROBE_PASS);
    b.set(SetSpec::points("probes", PROBES, "probe_x"));
    let s = spec(b.scene);
    // The groups address particles by id, which a scene whose particles are born and
    // die cannot (see floe_engine::population).
    if s.per_step(b.scene.particle_spacing) == 0 && s.lifetime.is_none() {
        let n = b.count(PARTICLES) as u32;
        let mut lists = vec![Vec::new(); GROUP_COUNT];
        for id in 0..n {
            for g in groups_of(id) {
                lists[g].push(id);
            }
        }
        b.map(&GROUPS, &lists);
        for spec in [&GROUP_X, &GROUP_X_SUM, &GROUP_SUM_SPREAD, &GROUP_SUMS] {
            b.zeros(spec);
        }
        for pass in [&GROUP_X_PASS, &GROUP_SUM_PASS, &GROUP_SPREAD_PASS, &MEMBER_SUM_PASS] {
            b.pass(pass);
        }
    }
    b.zeros(&DEPTH);
    b.pass(&FLOOR_PROJECT);
    b.pass(&FLOOR_DEPTH);
    let Some(Column::Vec3(initial)) = b.column("x") else { unreachable!("the core allocates positions first") };
    let floor = initial.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    if s.births as usize > initial.len() {
        return Err(BuildError::Backend(format!(
            "tracer.births: at most the {} initial positions, got {}",
            initial.len(),
            s.births
        )));
    }
    let births = match &s.body {
        Some(body) => {
            let bounds = floe_engine::math::Aabb::new(body.min.into(), body.max.into());
            let mesh = body.mesh.load().map_err(|e| BuildError::Mesh(format!("tracer.body.mesh: {e}")))?;
            mesh.fitted(bounds).fill_with(body.mesh.fill, bounds, b.scene.particle_spacing)
        }
        None => initial[..s.births as usize].to_vec(),
    };
    if !births.is_empty() {
        b.reserve(s.room(b.scene.particle_spacing) as usize);
        b.emitter(Emitter { name: "tracer.births", emit });
    }
    if s.lifetime.is_some() {
        b.removal();
        b.pass(&EXPIRE);
    }
    let d = b.domain();
    let columns = floe_proto::GridInfo {
        origin: d.min.to_array(),
        size: (d.max - d.min).to_array(),
        dims: [COLUMN_CELLS, 1, COLUMN_CELLS],
    };
    b.space(COLUMNS, (COLUMN_CELLS * COLUMN_CELLS) as usize);
    b.zeros(&COLUMN_COUNT);
    b.pass(&COLUMNS_PASS);
    b.set(SetSpec::grid(COLUMNS, COLUMNS, columns));
    b.channel(ChannelSpec {
        name: "column_count",
        unit: "",
        components: 1,
        exact: false,
        set: COLUMNS,
        module: "tracer",
        about: "Particles above each cell.",
        source: Source::Attr("column_count"),
    });
    if b.count(floe_engine::terrain::GROUND_SPACE) > 0 {
        b.pass(&RAISE_GROUND);
    }
    let lifetime = s.lifetime.unwrap_or(f32::INFINITY);
    let aged = b.materials().iter().position(|m| m.name == AGED).map_or(0, |i| i as u32);
    if s.phase_age.is_some() {
        b.pass(&PHASE);
    }
    let phase_age = s.phase_age.unwrap_or(f32::INFINITY);
    b.set_consts(TracerConsts { floor, columns, births, lifetime, phase_age, aged });
    b.position_solve(FLOOR_SOLVE);
    b.channel(ChannelSpec {
        name: "age",
        unit: "s",
        components: 1,
        exact: false,
        set: PARTICLES,
        module: "tracer",
        about: "Time since the scene started.",
        source: Source::Attr("age"),
    });
    b.channel(ChannelSpec {
        name: "spin",
        unit: "",
        components: 4,
        exact: false,
        set: PARTICLES,
        module: "tracer",
        about: "Orientation (quaternion x, y, z, w).",
        source: Source::Attr("spin"),
    });
    b.channel(ChannelSpec {
        name: "probe_age",
        unit: "s",
        components: 1,
        exact: false,
        set: "probes",
        module: "tracer",
        about: "Mean particle age.",
        source: Source::Attr("probe_age"),
    });
    Ok(())
}
