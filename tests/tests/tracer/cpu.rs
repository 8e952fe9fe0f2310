//! The tracer's passes on the CPU (the GPU's kernels in `gpu.rs` do the same).

use super::{COLOURS, RISE, TracerConsts, column_of};
use floe_engine::cpu::{CpuCx, CpuPass};
use floe_engine::math::{Mat3, Quat, Vec3};

/// `age += dt` for every particle.
#[derive(Debug)]
pub(super) struct Age;

impl CpuPass for Age {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let h = cx.attrs.handle::<f32>("age");
        cx.attrs.get_mut(h).iter_mut().for_each(|a| *a += dt);
    }
}

/// `spin = rot_y(dt) spin`, `frame = R(spin)`.
#[derive(Debug)]
pub(super) struct Spin;

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
pub(super) struct Probe;

impl CpuPass for Probe {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let ages = cx.attrs.get(cx.attrs.handle::<f32>("age"));
        let mean = ages.iter().map(|&a| f64::from(a)).sum::<f64>() / ages.len().max(1) as f64;
        let h = cx.attrs.handle::<f32>("probe_age");
        cx.attrs.get_mut(h).iter_mut().for_each(|p| *p = mean as f32);
    }
}

/// Particles of colour `sweep` (`id % 4`) below the floor are lifted onto it.
#[derive(Debug)]
pub(super) struct FloorProject;

impl CpuPass for FloorProject {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let floor = cx.model.consts::<TracerConsts>().floor;
        let (x, id) = (cx.attrs.handle::<Vec3>("x"), cx.attrs.handle::<u32>("id"));
        let mut pos = cx.attrs.take(x);
        for (p, &id) in pos.iter_mut().zip(cx.attrs.get(id)) {
            if id % COLOURS == cx.sweep {
                p.y = p.y.max(floor);
            }
        }
        cx.attrs.put(x, pos);
    }
}

/// `tracer_depth = max(0, floor - y)`.
#[derive(Debug)]
pub(super) struct FloorDepth;

impl CpuPass for FloorDepth {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let floor = cx.model.consts::<TracerConsts>().floor;
        let (x, d) = (cx.attrs.handle::<Vec3>("x"), cx.attrs.handle::<f32>("tracer_depth"));
        let mut depth = cx.attrs.take(d);
        for (d, p) in depth.iter_mut().zip(cx.attrs.get(x)) {
            *d = (floor - p.y).max(0.0);
        }
        cx.attrs.put(d, depth);
    }
}

/// Counts the particles above each cell of the columns' grid.
#[derive(Debug)]
pub(super) struct Columns;

impl CpuPass for Columns {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let grid = cx.model.consts::<TracerConsts>().columns;
        let c = cx.attrs.handle::<f32>("column_count");
        let mut counts = cx.attrs.take(c);
        counts.iter_mut().for_each(|n| *n = 0.0);
        for &p in cx.attrs.get(cx.attrs.handle::<Vec3>("x")) {
            if let Some(k) = column_of(&grid, p) {
                counts[k] += 1.0;
            }
        }
        cx.attrs.put(c, counts);
    }
}

/// `ground_height += RISE dt`.
#[derive(Debug)]
pub(super) struct RaiseGround;

impl CpuPass for RaiseGround {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let rise = RISE * cx.dt;
        let h = cx.attrs.handle::<f32>("ground_height");
        cx.attrs.get_mut(h).iter_mut().for_each(|g| *g += rise);
    }
}

/// Marks the particles older than the lifetime for removal.
#[derive(Debug)]
pub(super) struct Expire;

impl CpuPass for Expire {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let lifetime = cx.model.consts::<TracerConsts>().lifetime;
        let r = cx.attrs.handle::<f32>("remove");
        let mut remove = cx.attrs.take(r);
        for (r, &age) in remove.iter_mut().zip(cx.attrs.get(cx.attrs.handle::<f32>("age"))) {
            *r += if age > lifetime { 1.0 } else { 0.0 };
        }
        cx.attrs.put(r, remove);
    }
}

/// Particles older than the phase age change into the phase `aged`.
#[derive(Debug)]
pub(super) struct Phase;

impl CpuPass for Phase {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<TracerConsts>();
        let (phase_age, aged) = (c.phase_age, c.aged);
        let m = cx.attrs.handle::<u32>("material");
        let mut material = cx.attrs.take(m);
        for (m, &age) in material.iter_mut().zip(cx.attrs.get(cx.attrs.handle::<f32>("age"))) {
            if age > phase_age {
                *m = aged;
            }
        }
        cx.attrs.put(m, material);
    }
}
