//! The shape matching's own CPU passes (the map's generic passes do the sums): a
//! membership's position relative to its cluster's particle, its moment, a
//! cluster's rotation and centre, a membership's way to its goal and weight, a
//! particle's move by the weighted mean of its ways.

use super::{
    CENTRE, CLUSTER_INERTIA, CLUSTER_LIVE, CLUSTER_MOMENT, CLUSTER_SPIN, CLUSTER_SUM, CLUSTER_V, CLUSTERS, COLOUR,
    DEFORMATION, MEMBER_INERTIA, MEMBER_MOMENT, MEMBER_SPIN, MEMBER_V, MEMBER_WAY, MEMBER_WEIGHT, MEMBER_X,
    MIN_MEMBERS, NONRIGID, OMEGA, OWNER, RESIDUAL, REST, REST_CENTRE, ROTATION, SHARE, SolidConsts, V_MEAN, WAY_SUM,
    WEIGHT_SUM,
    spec::{ClusterSolver, Rotation},
};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Mat3, Quat, Vec3};
use glam::Vec4;
use rayon::prelude::*;

/// Per cluster of a melting body: which members hold (`super::LEAVE`), in
/// membership order as the GPU's `leave.wgsl`.
#[derive(Debug)]
pub struct Leave;

impl CpuPass for Leave {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SolidConsts>();
        let a = &mut *cx.attrs;
        let h = a.handle::<u32>(CLUSTERS.live.name);
        let mut live = a.take(h);
        let (start, len) = (a.get(a.handle::<u32>(CLUSTERS.start.name)), a.get(a.handle::<u32>(CLUSTERS.len.name)));
        let (member, owner) = (a.get(a.handle::<u32>(CLUSTERS.member.name)), a.get(a.handle::<u32>(OWNER.name)));
        let (slot, x) = (a.get(a.handle::<u32>("slot_of")), a.get(a.handle::<Vec3>("x")));
        let material = a.get(a.handle::<u32>("material"));
        let r2 = c.radius * c.radius;
        for s in 0..start.len() {
            let span = start[s] as usize..(start[s] + len[s]) as usize;
            let origin = x[slot[owner[s] as usize] as usize];
            let mut held = 0;
            for k in span.clone() {
                let i = slot[member[k] as usize] as usize;
                let elastic = c.elastic >> material[i] & 1 == 1;
                live[k] = match (elastic, live[k] == 1) {
                    (false, _) => 0,
                    (true, true) => 1,
                    (true, false) => 2 * u32::from(x[i].distance_squared(origin) <= r2),
                };
                held += u32::from(live[k] > 0);
            }
            if held < MIN_MEMBERS {
                live[span].fill(0);
            }
        }
        a.put(h, live);
    }
}

/// Per membership rejoining its cluster (`super::REJOIN`): its new rest offset.
#[derive(Debug)]
pub struct Rejoin;

impl CpuPass for Rejoin {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hr, hl) = (a.handle::<Vec3>(REST.name), a.handle::<u32>(CLUSTERS.live.name));
        let (mut rest, mut live) = (a.take(hr), a.take(hl));
        let (x, segment) = (a.get(a.handle::<Vec3>(MEMBER_X.name)), a.get(a.handle::<u32>(CLUSTERS.segment.name)));
        let (rotation, centre) = (a.get(a.handle::<Quat>(ROTATION.name)), a.get(a.handle::<[f32; 4]>(CENTRE.name)));
        rest.par_iter_mut().zip(live.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (q, l))| {
            if *l == 2 {
                let s = segment[k] as usize;
                (*q, *l) = (rotation[s].conjugate() * (x[k] - Vec4::from(centre[s]).truncate()), 1);
            }
        });
        a.put(hr, rest);
        a.put(hl, live);
    }
}

/// Per cluster: its live members and the mean of their rest offsets (0 while
/// all are live in a body that does not melt).
#[derive(Debug)]
pub struct Live;

impl CpuPass for Live {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let melting = cx.model.consts::<SolidConsts>().melting;
        let a = &mut *cx.attrs;
        let (hn, hc) = (a.handle::<u32>(CLUSTER_LIVE.name), a.handle::<Vec3>(REST_CENTRE.name));
        let (mut count, mut centre) = (a.take(hn), a.take(hc));
        let (start, len) = (a.get(a.handle::<u32>(CLUSTERS.start.name)), a.get(a.handle::<u32>(CLUSTERS.len.name)));
        let (live, rest) = (a.get(a.handle::<u32>(CLUSTERS.live.name)), a.get(a.handle::<Vec3>(REST.name)));
        count.par_iter_mut().zip(centre.par_iter_mut()).enumerate().with_min_len(1024).for_each(|(s, (n, q))| {
            let span = start[s] as usize..(start[s] + len[s]) as usize;
            let (mut held, mut sum) = (0, Vec3::ZERO);
            for k in span {
                if live[k] == 1 {
                    (held, sum) = (held + 1, sum + rest[k]);
                }
            }
            *n = held;
            *q = if (melting || held < len[s]) && held > 0 { sum / held as f32 } else { Vec3::ZERO };
        });
        a.put(hn, count);
        a.put(hc, centre);
    }
}

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
        let live = a.get(a.handle::<u32>(CLUSTER_LIVE.name));
        let rest = a.get(a.handle::<Vec3>(REST.name));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, m)| {
            let s = segment[k] as usize;
            if !c.active(colour[s], sweep) {
                return;
            }
            let p = x[k] - sum[s] / live[s].max(1) as f32;
            *m = Mat3::from_cols(p * rest[k].x, p * rest[k].y, p * rest[k].z);
        });
        a.put(h, out);
    }
}

/// Per cluster matched in this sweep: its rotation from the summed moment,
/// warm-started from the rotation it had (the state `cluster_rotation`), and
/// the origin of its goals: the live members' centre less the rotated mean of
/// their rest offsets (the centre itself while every member is live), with the
/// cluster's share of its ways in `w`. The moment needs no such shift: the
/// members' offsets from their centre sum to 0.
#[derive(Debug)]
pub struct Rotate;

impl CpuPass for Rotate {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let how = c.rotation;
        let a = &mut *cx.attrs;
        let (hr, hc) = (a.handle::<Quat>(ROTATION.name), a.handle::<[f32; 4]>(CENTRE.name));
        let (mut rotation, mut centre) = (a.take(hr), a.take(hc));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        let moment = a.get(a.handle::<Mat3>(CLUSTER_MOMENT.name));
        let sum = a.get(a.handle::<Vec3>(CLUSTER_SUM.name));
        let (live, rest) = (a.get(a.handle::<u32>(CLUSTER_LIVE.name)), a.get(a.handle::<Vec3>(REST_CENTRE.name)));
        let share = a.get(a.handle::<f32>(SHARE.name));
        rotation.par_iter_mut().zip(centre.par_iter_mut()).enumerate().with_min_len(1024).for_each(|(s, (q, m))| {
            if !c.active(colour[s], sweep) {
                return;
            }
            *q = match how {
                Rotation::Iterative => super::polar::iterative(moment[s], *q, super::POLAR_ITERATIONS),
                Rotation::Eigen => super::polar::eigen(moment[s]),
            };
            *m = (sum[s] / live[s].max(1) as f32 - *q * rest[s]).extend(share[s]).to_array();
        });
        a.put(hr, rotation);
        a.put(hc, centre);
    }
}

/// Per membership: the way to its goal, `g_k - x_k = R q_k + c - x_k` (the
/// thesis's eq. 2.19, all relative to the cluster's own particle), times its
/// weight, 1 (Jacobi, and the clusters of this sweep's colour); under weighted
/// Jacobi the way alone and its length, which [`Weigh`] turns into the cluster's
/// weight. A cluster of another colour has no way and
/// [`SolidConsts::idle_weight`]. Under conserving shares the way is also scaled
/// by its cluster's share (`w` of its centre).
#[derive(Debug)]
pub struct Way;

impl CpuPass for Way {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (c, sweep) = (cx.model.consts::<SolidConsts>(), cx.sweep);
        let a = &mut *cx.attrs;
        let (hw, hk) = (a.handle::<Vec3>(MEMBER_WAY.name), a.handle::<f32>(MEMBER_WEIGHT.name));
        let (mut way, mut weight) = (a.take(hw), a.take(hk));
        let (rotation, centre) = (a.get(a.handle::<Quat>(ROTATION.name)), a.get(a.handle::<[f32; 4]>(CENTRE.name)));
        let colour = a.get(a.handle::<u32>(COLOUR.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let (rest, x) = (a.get(a.handle::<Vec3>(REST.name)), a.get(a.handle::<Vec3>(MEMBER_X.name)));
        let conserving = c.conserving();
        way.par_iter_mut().zip(weight.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (d, w))| {
            let s = segment[k] as usize;
            if !c.active(colour[s], sweep) {
                (*d, *w) = (Vec3::ZERO, c.idle_weight());
                return;
            }
            let origin = Vec4::from(centre[s]);
            let to_goal = rotation[s] * rest[k] - (x[k] - origin.truncate());
            *w = if c.solver == ClusterSolver::WeightedJacobi { to_goal.length() } else { 1.0 };
            *d = if conserving { to_goal * origin.w } else { to_goal };
        });
        a.put(hw, way);
        a.put(hk, weight);
    }
}

/// Weighted Jacobi (the first thesis's eqs. 2.33-2.35): each membership's way and
/// weight by its cluster's deformation `d_i` (the summed distance of its members
/// from their goals, `solid.deformation_sum`), so a particle moves by
/// `sum_i d_i (g_i - x) / sum_i d_i` over its clusters: the clusters that deform
/// more have more say, and every goal of one cluster the same.
#[derive(Debug)]
pub struct Weigh;

impl CpuPass for Weigh {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hw, hk) = (a.handle::<Vec3>(MEMBER_WAY.name), a.handle::<f32>(MEMBER_WEIGHT.name));
        let (mut way, mut weight) = (a.take(hw), a.take(hk));
        let deformation = a.get(a.handle::<f32>(DEFORMATION.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        way.par_iter_mut().zip(weight.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (d, w))| {
            let cluster = deformation[segment[k] as usize];
            (*d, *w) = (*d * cluster, cluster);
        });
        a.put(hw, way);
        a.put(hk, weight);
    }
}

/// Each particle moves by `alpha` of the weighted mean of its ways (the Jacobi
/// solvers' eqs. 2.31 and 2.35, a colour's clusters in a coloured sweep; under
/// conserving shares their sum, each already scaled by its cluster's share), times
/// `1 - beta` where the bodies melt (the blend of the first thesis's eqs.
/// 2.39-2.40: the move is the solid's update over the fluid's, so the particle
/// ends at `beta` of the fluid's position and `1 - beta` of the solid's, and its
/// velocity, `v += (x - x_predicted) / dt`, likewise), and no further than its
/// room (`SolidConsts::room`: out of the walls); its residual is the largest such
/// mean over the iteration's sweeps (m).
#[derive(Debug)]
pub struct Project;

impl CpuPass for Project {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SolidConsts>();
        let (alpha, (low, high), first, conserving) = (c.iteration_alpha(), c.room, cx.sweep == 0, c.conserving());
        let a = &mut *cx.attrs;
        let (hx, hr) = (a.handle::<Vec3>("x"), a.handle::<f32>(RESIDUAL.name));
        let (mut x, mut residual) = (a.take(hx), a.take(hr));
        let (way, weight) = (a.get(a.handle::<Vec3>(WAY_SUM.name)), a.get(a.handle::<f32>(WEIGHT_SUM.name)));
        let beta = a.find::<f32>(crate::quantities::LIQUID_FRACTION.name).map(|h| a.get(h));
        x.par_iter_mut().zip(residual.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (x, r))| {
            if first {
                *r = 0.0;
            }
            if weight[i] > 0.0 {
                let mean = if conserving { way[i] } else { way[i] / weight[i] };
                *r = r.max(mean.length());
                let share = beta.map_or(alpha, |b| alpha * (1.0 - b[i]));
                *x = (*x + mean * share).clamp(low, high);
            }
        });
        a.put(hx, x);
        a.put(hr, residual);
    }
}

/// Alpha once per step (the first thesis's eq. 2.23): each elastic particle's move
/// over the step's shape solve, which took it to its goals, scaled by alpha,
/// `x = x_predicted + alpha (x - x_predicted)`. (A particle of another material
/// did not move in the solve; a melting one moved by `1 - beta` of its way.)
#[derive(Debug)]
pub struct Stiffen;

impl CpuPass for Stiffen {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let c = cx.model.consts::<SolidConsts>();
        let a = &mut *cx.attrs;
        let hx = a.handle::<Vec3>("x");
        let mut x = a.take(hx);
        let from = a.get(a.handle::<Vec3>("x_predicted"));
        let material = a.find::<u32>("material").map(|h| a.get(h));
        let alpha = c.stiffness;
        x.par_iter_mut().enumerate().with_min_len(4096).for_each(|(i, x)| {
            if c.elastic >> material.map_or(0, |m| m[i]) & 1 == 1 {
                *x = from[i] + (*x - from[i]) * alpha;
            }
        });
        a.put(hx, x);
    }
}

/// Per membership, for every cluster: its member's position at the middle of the
/// step, `x - v dt / 2`, relative to the cluster's own particle's, and its
/// velocity. The step's velocity is the chord from the position before the step to
/// the one after (`v += (x - x_predicted) / dt`), which a rigid motion gives at the
/// middle of the step: fitted at the step's end, a spinning body's chords leave a
/// radial part the mean over a surface particle's clusters does not cancel, and a
/// free spin's linear momentum drifted by 2 % in 10 s (0.26 % at the middle).
#[derive(Debug)]
pub struct Motion;

impl CpuPass for Motion {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hx, hv) = (a.handle::<Vec3>(MEMBER_X.name), a.handle::<Vec3>(MEMBER_V.name));
        let (mut rel, mut vel) = (a.take(hx), a.take(hv));
        let (x, v, slot) =
            (a.get(a.handle::<Vec3>("x")), a.get(a.handle::<Vec3>("v")), a.get(a.handle::<u32>("slot_of")));
        let (member, segment) =
            (a.get(a.handle::<u32>(CLUSTERS.member.name)), a.get(a.handle::<u32>(CLUSTERS.segment.name)));
        let owner = a.get(a.handle::<u32>(OWNER.name));
        let back = 0.5 * cx.dt;
        rel.par_iter_mut().zip(vel.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (r, u))| {
            let i = slot[member[k] as usize] as usize;
            let o = slot[owner[segment[k] as usize] as usize] as usize;
            *r = (x[i] - v[i] * back) - (x[o] - v[o] * back);
            *u = v[i];
        });
        a.put(hx, rel);
        a.put(hv, vel);
    }
}

/// Per membership: its angular momentum `r x v` and inertia `|r|^2 1 - r r^T`
/// about its cluster's centre (per unit mass: masses are equal within a body).
#[derive(Debug)]
pub struct Spin;

impl CpuPass for Spin {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hs, hi) = (a.handle::<Vec3>(MEMBER_SPIN.name), a.handle::<Mat3>(MEMBER_INERTIA.name));
        let (mut spin, mut inertia) = (a.take(hs), a.take(hi));
        let (x, v) = (a.get(a.handle::<Vec3>(MEMBER_X.name)), a.get(a.handle::<Vec3>(MEMBER_V.name)));
        let (sum, live) = (a.get(a.handle::<Vec3>(CLUSTER_SUM.name)), a.get(a.handle::<u32>(CLUSTER_LIVE.name)));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        spin.par_iter_mut().zip(inertia.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (l, i))| {
            let s = segment[k] as usize;
            let r = x[k] - sum[s] / live[s].max(1) as f32;
            *l = r.cross(v[k]);
            *i = inertia_of(r);
        });
        a.put(hs, spin);
        a.put(hi, inertia);
    }
}

/// The inertia of a unit mass at `r`: `|r|^2 1 - r r^T`.
fn inertia_of(r: Vec3) -> Mat3 {
    Mat3::from_diagonal(Vec3::splat(r.length_squared())) - Mat3::from_cols(r * r.x, r * r.y, r * r.z)
}

/// Per cluster: its rigid motion, the mean velocity of its live members and the
/// angular velocity `I^-1 L`; the inertia is regularised by a millionth of its
/// trace, which leaves a straight cluster (two members) no turn about its own
/// line, where its angular momentum has none. A cluster with no live member has
/// none.
#[derive(Debug)]
pub struct Rigid;

/// The share of its trace added to a cluster's inertia before inverting it.
pub const INERTIA_REGULARISATION: f32 = 1e-6;

impl CpuPass for Rigid {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hv, hw) = (a.handle::<Vec3>(V_MEAN.name), a.handle::<Vec3>(OMEGA.name));
        let (mut mean, mut omega) = (a.take(hv), a.take(hw));
        let (sum, live) = (a.get(a.handle::<Vec3>(CLUSTER_V.name)), a.get(a.handle::<u32>(CLUSTER_LIVE.name)));
        let (spin, inertia) =
            (a.get(a.handle::<Vec3>(CLUSTER_SPIN.name)), a.get(a.handle::<Mat3>(CLUSTER_INERTIA.name)));
        mean.par_iter_mut().zip(omega.par_iter_mut()).enumerate().with_min_len(1024).for_each(|(s, (m, w))| {
            (*m, *w) = rigid(sum[s], live[s], spin[s], inertia[s]);
        });
        a.put(hv, mean);
        a.put(hw, omega);
    }
}

/// A cluster's rigid motion from its sums (see [`Rigid`]).
fn rigid(sum: Vec3, live: u32, spin: Vec3, inertia: Mat3) -> (Vec3, Vec3) {
    if live == 0 {
        return (Vec3::ZERO, Vec3::ZERO);
    }
    let trace = inertia.x_axis.x + inertia.y_axis.y + inertia.z_axis.z;
    let regular = inertia + Mat3::from_diagonal(Vec3::splat(INERTIA_REGULARISATION * trace + f32::MIN_POSITIVE));
    (sum / live as f32, regular.inverse() * spin)
}

/// Per membership: its member's velocity under its cluster's rigid motion,
/// `v_c + omega x r` (weight 1).
#[derive(Debug)]
pub struct RigidWay;

impl CpuPass for RigidWay {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let a = &mut *cx.attrs;
        let (hw, hk) = (a.handle::<Vec3>(MEMBER_WAY.name), a.handle::<f32>(MEMBER_WEIGHT.name));
        let (mut way, mut weight) = (a.take(hw), a.take(hk));
        let x = a.get(a.handle::<Vec3>(MEMBER_X.name));
        let (sum, live) = (a.get(a.handle::<Vec3>(CLUSTER_SUM.name)), a.get(a.handle::<u32>(CLUSTER_LIVE.name)));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let (mean, omega) = (a.get(a.handle::<Vec3>(V_MEAN.name)), a.get(a.handle::<Vec3>(OMEGA.name)));
        way.par_iter_mut().zip(weight.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(k, (d, w))| {
            let s = segment[k] as usize;
            let r = x[k] - sum[s] / live[s].max(1) as f32;
            (*d, *w) = (mean[s] + omega[s].cross(r), 1.0);
        });
        a.put(hw, way);
        a.put(hk, weight);
    }
}

/// Each particle of a cluster: its velocity moves by `damping` (times `1 - beta`
/// where the bodies melt) of the way to the mean of its clusters' rigid
/// velocities; `solid_nonrigid` keeps that way's length before the move (m/s).
#[derive(Debug)]
pub struct Damp;

impl CpuPass for Damp {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let k = cx.model.consts::<SolidConsts>().damping;
        let a = &mut *cx.attrs;
        let (hv, hn) = (a.handle::<Vec3>("v"), a.handle::<f32>(NONRIGID.name));
        let (mut v, mut nonrigid) = (a.take(hv), a.take(hn));
        let (way, weight) = (a.get(a.handle::<Vec3>(WAY_SUM.name)), a.get(a.handle::<f32>(WEIGHT_SUM.name)));
        let beta = a.find::<f32>(crate::quantities::LIQUID_FRACTION.name).map(|h| a.get(h));
        v.par_iter_mut().zip(nonrigid.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (v, n))| {
            *n = 0.0;
            if weight[i] > 0.0 {
                let to_rigid = way[i] / weight[i] - *v;
                *n = to_rigid.length();
                *v += to_rigid * beta.map_or(k, |b| k * (1.0 - b[i]));
            }
        });
        a.put(hv, v);
        a.put(hn, nonrigid);
    }
}
