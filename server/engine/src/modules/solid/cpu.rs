//! The shape matching's own CPU passes (the map's generic passes do the gathers
//! and sums): a membership's moment, a cluster's rotation and centre, a
//! membership's goal, a particle's projection towards the mean of its goals.

use super::{
    CENTRE, CLUSTER_MOMENT, CLUSTER_SUM, CLUSTERS, GOAL_SUM, MEMBER_GOAL, MEMBER_MOMENT, MEMBER_X, RESIDUAL, REST,
    ROTATION, SolidConsts, spec::Rotation,
};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Mat3, Quat, Vec3};
use rayon::prelude::*;

/// `A_k = (x_k - c) q_k^T` per membership, `c` its cluster's centre from the
/// summed positions (the first thesis's eq. 2.14, unit masses within a body).
#[derive(Debug)]
pub struct Moment;

impl CpuPass for Moment {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let h = a.handle::<Mat3>(MEMBER_MOMENT.name);
        let mut out = a.take(h);
        let x = a.get(a.handle::<Vec3>(MEMBER_X.name));
        let sum = a.get(a.handle::<Vec3>(CLUSTER_SUM.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let len = a.get(a.handle::<u32>(CLUSTERS.len.name));
        let rest = a.get(a.handle::<Vec3>(REST.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, m)| {
            let s = segment[k] as usize;
            let p = x[k] - sum[s] / len[s] as f32;
            *m = Mat3::from_cols(p * rest[k].x, p * rest[k].y, p * rest[k].z);
        });
        a.put(h, out);
    }
}

/// Per cluster: its centre and its rotation from the summed moment, warm-started
/// from the rotation it had (the state `cluster_rotation`).
#[derive(Debug)]
pub struct Rotate;

impl CpuPass for Rotate {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let how = cx.model.consts::<SolidConsts>().rotation;
        let a = &mut *cx.attrs;
        let (hr, hc) = (a.handle::<Quat>(ROTATION.name), a.handle::<Vec3>(CENTRE.name));
        let (mut rotation, mut centre) = (a.take(hr), a.take(hc));
        let moment = a.get(a.handle::<Mat3>(CLUSTER_MOMENT.name));
        let sum = a.get(a.handle::<Vec3>(CLUSTER_SUM.name));
        let len = a.get(a.handle::<u32>(CLUSTERS.len.name));
        rotation.par_iter_mut().zip(centre.par_iter_mut()).enumerate().with_min_len(1024).for_each(|(s, (q, c))| {
            *c = sum[s] / len[s] as f32;
            *q = match how {
                Rotation::Iterative => super::polar::iterative(moment[s], *q, super::POLAR_ITERATIONS),
                Rotation::Eigen => super::polar::eigen(moment[s]),
            };
        });
        a.put(hr, rotation);
        a.put(hc, centre);
    }
}

/// `g_k = R q_k + c` per membership (the thesis's eq. 2.19).
#[derive(Debug)]
pub struct Goal;

impl CpuPass for Goal {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let h = a.handle::<Vec3>(MEMBER_GOAL.name);
        let mut out = a.take(h);
        let (rotation, centre) = (a.get(a.handle::<Quat>(ROTATION.name)), a.get(a.handle::<Vec3>(CENTRE.name)));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let rest = a.get(a.handle::<Vec3>(REST.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, g)| {
            let s = segment[k] as usize;
            *g = rotation[s] * rest[k] + centre[s];
        });
        a.put(h, out);
    }
}

/// Jacobi (the thesis's eq. 2.31): each member of a cluster moves by `alpha` of
/// the way to the mean of its goals; the residual is that way's length (m).
#[derive(Debug)]
pub struct Project;

impl CpuPass for Project {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let alpha = cx.model.consts::<SolidConsts>().stiffness;
        let a = &mut *cx.attrs;
        let (hx, hr) = (a.handle::<Vec3>("x"), a.handle::<f32>(RESIDUAL.name));
        let (mut x, mut residual) = (a.take(hx), a.take(hr));
        let goal = a.get(a.handle::<Vec3>(GOAL_SUM.name));
        let id = a.get(a.handle::<u32>("id"));
        let count = a.get(a.handle::<u32>(CLUSTERS.count.name));
        x.par_iter_mut().zip(residual.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (x, r))| {
            let n = count.get(id[i] as usize).copied().unwrap_or(0);
            if n == 0 {
                *r = 0.0;
                return;
            }
            let way = goal[i] / n as f32 - *x;
            *r = way.length();
            *x += way * alpha;
        });
        a.put(hx, x);
        a.put(hr, residual);
    }
}
