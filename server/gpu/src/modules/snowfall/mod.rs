//! The snowfall module on the GPU: the births counted by one thread, the flakes
//! moved and landed by a thread per slot (landings counted with `u32` atomics, so
//! the counts are the CPU's whatever the threads' order), and the surface the next
//! flakes land on, by a thread per cell; the module uniform `snowfall` holds
//! [`SnowfallConsts`].

use crate::pass::{GpuPass, always};
use crate::passes::particle_kernel;
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::model::Model;
use floe_engine::modules::snowfall::{CELLS, COUNTERS, FLAKES, MAX_OBJECTS, SnowfallConsts};

/// The step's births.
pub static EMIT: GpuPass = GpuPass {
    name: "snowfall.emit",
    source: particle_kernel!("snowfall.wgsl", "emit.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "snowfall"), (U, "dt"), (W, "snowfall_tally"), (W, "snowfall_timer")],
    space: COUNTERS,
    when: always,
};

/// The flakes' motion and landing, and the births.
pub static FALL: GpuPass = GpuPass {
    name: "snowfall.fall",
    source: particle_kernel!("snowfall.wgsl", "fall.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "snowfall"),
        (U, "dt"),
        (W, "flake_x"),
        (W, "flake_v"),
        (W, "flake_age"),
        (W, "snowfall_tally"),
        (R, "snowfall_timer"),
        (R, "snow_surface"),
        (W, "ground_count"),
        (W, "top_count"),
    ],
    space: FLAKES,
    when: always,
};

/// The surface the next flakes land on.
pub static SURFACE: GpuPass = GpuPass {
    name: "snowfall.surface",
    source: particle_kernel!("snowfall.wgsl", "surface.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "snowfall"),
        (R, "ground_count"),
        (R, "top_count"),
        (R, "snow_bed"),
        (R, "snow_columns"),
        (W, "snow_surface"),
    ],
    space: CELLS,
    when: always,
};

/// The `snowfall` uniform (`Snowfall` in snowfall.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct SnowfallParams {
    area: [f32; 4],
    emit: [f32; 4],
    fall: [f32; 4],
    air: [f32; 4],
    more: [f32; 4],
    sizes: [u32; 4],
    grid: [f32; 4],
    turbulence: [f32; 4],
    objects: [[f32; 4]; 2 * MAX_OBJECTS],
}

/// The uniform's bytes, when the scene has the snowfall module.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    if !model.has_module("snowfall") {
        return None;
    }
    let c: &SnowfallConsts = model.consts();
    let mut u = SnowfallParams::zeroed();
    u.area = [c.area_min[0], c.area_min[1], c.area_max[0], c.area_max[1]];
    u.emit = [c.emit_min[0], c.emit_min[1], c.emit_max[0], c.emit_max[1]];
    u.fall = [c.height, c.floor, c.rate, c.terminal_speed];
    u.air = [c.tau, c.wind[0], c.wind[1], c.gusts];
    u.more = [c.gust_omega, c.flutter, c.max_age, c.depth_per_flake];
    u.sizes = [c.capacity, c.nx, c.nz, c.objects.len() as u32];
    u.grid = [c.origin[0], c.origin[1], c.cell, 0.0];
    let [amplitude, per_metre, per_second] = c.turbulence;
    u.turbulence = [amplitude, per_metre, per_second, 0.0];
    for (slot, o) in u.objects.chunks_exact_mut(2).zip(&c.objects) {
        slot.copy_from_slice(o);
    }
    Some(bytemuck::bytes_of(&u).to_vec())
}
