//! The shape matching's own CPU passes (the map's generic passes do the sums): a
//! membership's position relative to its cluster's particle, its moment, a
//! cluster's rotation and centre, a membership's way to its goal and weight, a
//! particle's move by the weighted mean of its ways.

use super::{
    CENTRE, CLUSTER_MOMENT, CLUSTER_SUM, CLUSTERS, COLOUR, MEMBER_MOMENT, MEMBER_WAY, MEMBER_WEIGHT, MEMBER_X, OWNER,
    RESIDUAL, REST, ROTATION, SolidConsts, WAY_SUM, WEIGHT_SUM,
    spec::{ClusterSolver, Rotation},
};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Mat3, Quat, Vec3};
use rayon::prelude::*;

/// `x_k = x[member k] - x[the cluster's own particle]` per membership of a
/// cluster matched in this sweep.
#[derive(Debug)]
pub struct GatherRelative;

impl CpuPass for GatherRelative {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let a = &mut *cx.attrs;
        let h = a.handle::<Vec3>(MEMBER_X.name);
        let mut out = a.take(h);
        let x = a.get(a.handle::<Vec3>("x"));
        let slot = a.get(a.handle::<u32>("slot_of"));
        let member = a.get(a.handle::<u32>(CLUSTERS.member.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let owner = a.get(a.handle::<u32>(OWNER.name));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, r)| {
            let s = segment[k] as usize;
            if !c.active(colour[s], sweep) {
                return;
            }
            let origin = x[slot[owner[s] as usize] as usize];
            *r = x[slot[member[k] as usize] as usize] - origin;
        });
        a.put(h, out);
    }
}

/// `A_k = (x_k - c) q_k^T` per membership of a cluster matched in this sweep, `c`
/// its cluster's centre from the summed positions (the first thesis's eq. 2.14,
/// unit masses within a body).
#[derive(Debug)]
pub struct Moment;

impl CpuPass for Moment {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let a = &mut *cx.attrs;
        let h = a.handle::<Mat3>(MEMBER_MOMENT.name);
        let mut out = a.take(h);
        let x = a.get(a.handle::<Vec3>(MEMBER_X.name));
        let sum = a.get(a.handle::<Vec3>(CLUSTER_SUM.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let len = a.get(a.handle::<u32>(CLUSTERS.len.name));
        let rest = a.get(a.handle::<Vec3>(REST.name));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, m)| {
            let s = segment[k] as usize;
            if !c.active(colour[s], sweep) {
                return;
            }
            let p = x[k] - sum[s] / len[s] as f32;
            *m = Mat3::from_cols(p * rest[k].x, p * rest[k].y, p * rest[k].z);
        });
        a.put(h, out);
    }
}

/// Per cluster matched in this sweep: its centre and its rotation from the
/// summed moment, warm-started from the rotation it had (the state
/// `cluster_rotation`).
#[derive(Debug)]
pub struct Rotate;

impl CpuPass for Rotate {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let how = c.rotation;
        let a = &mut *cx.attrs;
        let (hr, hc) = (a.handle::<Quat>(ROTATION.name), a.handle::<Vec3>(CENTRE.name));
        let (mut rotation, mut centre) = (a.take(hr), a.take(hc));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        let moment = a.get(a.handle::<Mat3>(CLUSTER_MOMENT.name));
        let sum = a.get(a.handle::<Vec3>(CLUSTER_SUM.name));
        let len = a.get(a.handle::<u32>(CLUSTERS.len.name));
        rotation.par_iter_mut().zip(centre.par_iter_mut()).enumerate().with_min_len(1024).for_each(|(s, (q, m))| {
            if !c.active(colour[s], sweep) {
                return;
            }
            *m = sum[s] / len[s] as f32;
            *q = match how {
                Rotation::Iterative => super::polar::iterative(moment[s], *q, super::POLAR_ITERATIONS),
                Rotation::Eigen => super::polar::eigen(moment[s]),
            };
        });
        a.put(hr, rotation);
        a.put(hc, centre);
    }
}

/// Per membership: the way to its goal, `g_k - x_k = R q_k + c - x_k` (the
/// thesis's eq. 2.19, all relative to the cluster's own particle), times its
/// weight: 1 (Jacobi, and the clusters of this sweep's colour), `|g_k - x_k|`
/// (weighted Jacobi, eq. 2.34); a cluster of another colour has no way and
/// [`SolidConsts::idle_weight`].
#[derive(Debug)]
pub struct Way;

impl CpuPass for Way {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let a = &mut *cx.attrs;
        let (hw, hk) = (a.handle::<Vec3>(MEMBER_WAY.name), a.handle::<f32>(MEMBER_WEIGHT.name));
        let (mut way, mut weight) = (a.take(hw), a.take(hk));
        let (rotation, centre) = (a.get(a.handle::<Quat>(ROTATION.name)), a.get(a.handle::<Vec3>(CENTRE.name)));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let (rest, x) = (a.get(a.handle::<Vec3>(REST.name)), a.get(a.handle::<Vec3>(MEMBER_X.name)));
        way.par_iter_mut().zip(weight.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (d, w))| {
            let s = segment[k] as usize;
            if !c.active(colour[s], sweep) {
                (*d, *w) = (Vec3::ZERO, c.idle_weight());
                return;
            }
            let to_goal = rotation[s] * rest[k] - (x[k] - centre[s]);
            *w = if c.solver == ClusterSolver::WeightedJacobi { to_goal.length() } else { 1.0 };
            *d = to_goal * *w;
        });
        a.put(hw, way);
        a.put(hk, weight);
    }
}

/// Each particle moves by `alpha` of the weighted mean of its ways (the Jacobi
/// solvers' eqs. 2.31 and 2.35, a colour's clusters in a coloured sweep), and no
/// further than its room (`SolidConsts::room`: out of the walls); its residual is
/// the largest such mean over the iteration's sweeps (m).
#[derive(Debug)]
pub struct Project;

impl CpuPass for Project {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SolidConsts>();
        let (alpha, (low, high), first) = (c.stiffness, c.room, cx.sweep == 0);
        let a = &mut *cx.attrs;
        let (hx, hr) = (a.handle::<Vec3>("x"), a.handle::<f32>(RESIDUAL.name));
        let (mut x, mut residual) = (a.take(hx), a.take(hr));
        let (way, weight) = (a.get(a.handle::<Vec3>(WAY_SUM.name)), a.get(a.handle::<f32>(WEIGHT_SUM.name)));
        x.par_iter_mut().zip(residual.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (x, r))| {
            if first {
                *r = 0.0;
            }
            if weight[i] > 0.0 {
                let mean = way[i] / weight[i];
                *r = r.max(mean.length());
                *x = (*x + mean * alpha).clamp(low, high);
            }
        });
        a.put(hx, x);
        a.put(hr, residual);
    }
}
