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

use floe_engine::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use floe_engine::channels::{ChannelSpec, SetSpec, Source};
use floe_engine::cpu::{CpuCx, CpuPass};
use floe_engine::guard::Bound;
use floe_engine::math::{Mat3, Quat, Vec3};
use floe_engine::model::{BuildError, ModelBuilder};
use floe_engine::module::ModuleDef;
use floe_engine::plan::{PassSpec, Stage};
use floe_engine::scene::Scene;

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "tracer",
    about: "Particle ages and probes (a module of the tests).",
    requires: &["fluid"],
    section: None,
    validate: |_, _| {},
    count: |_| vec![(PROBES, 4)],
    materials: |_| 0,
    claims: |_| Vec::new(),
    particles: |_, _| Ok(()),
    build,
    retune: |_, _| {},
    tunables: &[],
    cpu: &[("tracer.age", &Age), ("tracer.spin", &Spin), ("tracer.probe", &Probe)],
    presets: &[],
    dt_limit: |_| None,
    measures: |_| Vec::new(),
    cases: &[],
    stability: &[],
    bench: &[],
};

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
    tolerance: 0.0,
};

static PROBE_PASS: PassSpec = PassSpec {
    name: "tracer.probe",
    module: "tracer",
    stage: Stage::PostStep,
    reads: &["age"],
    writes: &["probe_age"],
    accumulates: &[],
    tolerance: 0.0,
};

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
    b.set(SetSpec { name: "probes", space: PROBES, position: "probe_x", id: None });
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

/// `age += dt` for every particle.
#[derive(Debug)]
struct Age;

impl CpuPass for Age {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let h = cx.attrs.handle::<f32>("age");
        cx.attrs.get_mut(h).iter_mut().for_each(|a| *a += dt);
    }
}

/// `spin = rot_y(dt) spin`, `frame = R(spin)`.
#[derive(Debug)]
struct Spin;

impl CpuPass for Spin {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let turn = Quat::from_rotation_y(cx.dt);
        let h = cx.attrs.handle::<Quat>("spin");
        cx.attrs.get_mut(h).iter_mut().for_each(|q| *q = (turn * *q).normalize());
        let spins = cx.attrs.get(h).to_vec();
        let f = cx.attrs.handle::<Mat3>("frame");
        cx.attrs.get_mut(f).iter_mut().zip(spins).for_each(|(m, q)| *m = Mat3::from_quat(q));
    }
}

/// Every probe gets the particles' mean age.
#[derive(Debug)]
struct Probe;

impl CpuPass for Probe {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let ages = cx.attrs.get(cx.attrs.handle::<f32>("age"));
        let mean = ages.iter().map(|&a| f64::from(a)).sum::<f64>() / ages.len().max(1) as f64;
        let h = cx.attrs.handle::<f32>("probe_age");
        cx.attrs.get_mut(h).iter_mut().for_each(|p| *p = mean as f32);
    }
}
