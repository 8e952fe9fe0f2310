//! The tracer's GPU half, registered from outside floe-gpu
//! (`floe_gpu::pass::register`): its own kernels (WGSL beside this file, after
//! floe-gpu's `common.wgsl`) and the core's generic map kernels
//! (`floe_gpu::map_pass!`).

use super::{COLOURS, COLUMNS as COLUMN_SPACE, PROBES, RISE, TracerConsts};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_gpu::pass::{GpuModule, GpuPass, always};
use floe_gpu::program::Access::{Read as R, ReadWrite as W, Uniform as U};

/// floe-gpu's prelude of every particle kernel, then the tracer's files.
macro_rules! kernel {
    ($($file:literal),+) => {
        concat!(include_str!("../../../server/gpu/src/passes/common.wgsl"), $("\n", include_str!($file)),+)
    };
}

/// The module's GPU half.
pub static MODULE: GpuModule = GpuModule {
    id: "tracer",
    passes: &[
        &AGE,
        &SPIN,
        &PROBE,
        &FLOOR_PROJECT,
        &FLOOR_DEPTH,
        &GROUP_X,
        &GROUP_SUM,
        &GROUP_SPREAD,
        &MEMBER_SUM,
        &COLUMNS,
        &RAISE_GROUND,
        &EXPIRE,
        &PHASE,
    ],
    uniforms: &[("tracer", uniform)],
};

static AGE: GpuPass = GpuPass {
    name: "tracer.age",
    source: kernel!("age.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (W, "age")],
    space: PARTICLES,
    when: always,
};

static SPIN: GpuPass = GpuPass {
    name: "tracer.spin",
    source: kernel!("spin.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "dt"), (W, "spin"), (W, "frame")],
    space: PARTICLES,
    when: always,
};

static PROBE: GpuPass = GpuPass {
    name: "tracer.probe",
    source: kernel!("tracer.wgsl", "probe.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (R, "age"), (W, "probe_age")],
    space: PROBES,
    when: always,
};

static FLOOR_PROJECT: GpuPass = GpuPass {
    name: "tracer.floor_project",
    source: kernel!("tracer.wgsl", "floor_project.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (U, "sweep"), (R, "id"), (W, "x")],
    space: PARTICLES,
    when: always,
};

static FLOOR_DEPTH: GpuPass = GpuPass {
    name: "tracer.floor_depth",
    source: kernel!("tracer.wgsl", "floor_depth.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (R, "x"), (W, "tracer_depth")],
    space: PARTICLES,
    when: always,
};

static COLUMNS: GpuPass = GpuPass {
    name: "tracer.columns",
    source: kernel!("tracer.wgsl", "columns.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (R, "x"), (W, "column_count")],
    space: COLUMN_SPACE,
    when: always,
};

static RAISE_GROUND: GpuPass = GpuPass {
    name: "tracer.raise_ground",
    source: kernel!("tracer.wgsl", "raise_ground.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (U, "dt"), (W, "ground_height")],
    space: floe_engine::terrain::GROUND_SPACE,
    when: always,
};

static EXPIRE: GpuPass = GpuPass {
    name: "tracer.expire",
    source: kernel!("tracer.wgsl", "expire.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (R, "age"), (W, "remove")],
    space: PARTICLES,
    when: always,
};

static PHASE: GpuPass = GpuPass {
    name: "tracer.phase",
    source: kernel!("tracer.wgsl", "phase.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "tracer"), (R, "age"), (W, "x")],
    space: PARTICLES,
    when: always,
};

static GROUP_X: GpuPass =
    floe_gpu::map_pass!(gather "tracer.group_x", map "tracer_groups", words 4, from "x" into "tracer_groups_x");
static GROUP_SUM: GpuPass = floe_gpu::map_pass!(segment_sum "tracer.group_sum", map "tracer_groups", segments "groups", words 4, from "tracer_groups_x" into "group_x_sum");
static GROUP_SPREAD: GpuPass = floe_gpu::map_pass!(spread "tracer.group_spread", map "tracer_groups", words 4, from "group_x_sum" into "tracer_groups_sum");
static MEMBER_SUM: GpuPass = floe_gpu::map_pass!(member_sum "tracer.member_sum", map "tracer_groups", members "particles", words 4, from "tracer_groups_sum" into "group_sums");

/// The `tracer` uniform (`Tracer` in tracer.wgsl).
fn uniform(model: &Model) -> Option<Vec<u8>> {
    let c = model.has_module("tracer").then(|| model.consts::<TracerConsts>())?;
    let g = &c.columns;
    let f = |x: f32| x.to_bits();
    let words = [
        f(c.floor),
        COLOURS,
        model.layout.count(PROBES) as u32,
        f(RISE),
        f(g.origin[0]),
        f(g.origin[1]),
        f(g.origin[2]),
        f(c.lifetime),
        f(g.size[0]),
        f(g.size[1]),
        f(g.size[2]),
        f(c.phase_age),
        g.dims[0],
        g.dims[1],
        g.dims[2],
        c.aged,
    ];
    Some(words.iter().flat_map(|w| w.to_le_bytes()).collect())
}
