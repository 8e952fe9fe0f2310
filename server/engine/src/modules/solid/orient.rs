//! Oriented particles (Mueller and Chentanez 2011, "Solid Simulation with
//! Oriented Particles"; the first thesis's eqs. 2.25-2.30 and 2.36-2.38): each
//! particle of an elastic body is an ellipsoid with radii `a, b, c` along its own
//! axes, an orientation `q` and an angular velocity `w`.
//!
//! - **Prediction** (eq. 2.28), once a step before the cluster solve: the
//!   orientation turned by `w dt` (none below 1e-9 rad/s), the one before kept.
//! - **The ellipsoid's moment** (eqs. 2.26-2.27), each iteration: every member adds
//!   `R_k D` to its cluster's moment, `D = m/5 diag(a^2, b^2, c^2)` (unit masses)
//!   and `R_k` its predicted orientation. The thesis writes `D R`; `R D` is the
//!   moment of the rotated ellipsoid, `sum (R x) x^T dm`, and the two agree for the
//!   thesis's `a = b = c`.
//! - **Blending** (eqs. 2.29, 2.36-2.38), after the step: each membership's
//!   cluster rotation, its sign chosen against the member's orientation before the
//!   step (eq. 2.37), summed per particle and normalised (QLERP), or their turns
//!   from that orientation averaged as logarithms and exponentiated (ExpMap); the
//!   rest orientation is the identity, so the blend is the new orientation. The angular velocity follows from the
//!   turn it made (eq. 2.30: `w = axis * angle / dt` of `q_new q_old^-1`, taken
//!   the short way, as `w >= 0`; none below 1e-9 rad).

use super::{CLUSTER_MOMENT, CLUSTERS, ROTATION, SolidConsts, spec::Blend};
use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Mat3, Quat, Vec3};
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

const fn attr(name: &'static str, elem: Elem, unit: &'static str, role: Role, space: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role, added_later: false, space, module: "solid", about: name }
}

/// Each particle's orientation (its rotation from rest).
pub static ORIENTATION: AttrSpec = attr("solid_orientation", Elem::Quat, "", Role::State, PARTICLES);
/// Each particle's angular velocity (rad/s).
pub static SPIN: AttrSpec = attr("solid_spin", Elem::Vec3, "rad/s", Role::State, PARTICLES);
/// Each particle's orientation before this step's prediction.
pub static BEFORE: AttrSpec = attr("solid_orientation_before", Elem::Quat, "", Role::Derived, PARTICLES);
/// Each membership's cluster rotation with its sign (QLERP) or its logarithm (ExpMap).
pub static MEMBER_TURN: AttrSpec = attr("solid_clusters_turn", Elem::Quat, "", Role::Derived, "solid_clusters");
/// Each particle's sum of its memberships' turns.
pub static TURN_SUM: AttrSpec = attr("solid_turn_sum", Elem::Quat, "", Role::Derived, PARTICLES);

/// Prediction (a start of the cluster solve).
pub static PREDICT: PassSpec = PassSpec::solve(
    "solid",
    "solid.orient_predict",
    &["solid_spin"],
    &["solid_orientation_before"],
    &["solid_orientation"],
);
/// The members' ellipsoids into their clusters' moments.
pub static ELLIPSOID: PassSpec = PassSpec::solve(
    "solid",
    "solid.ellipsoid",
    &[
        "solid_clusters_start",
        "solid_clusters_len",
        "solid_clusters_live",
        "solid_clusters_member",
        "slot_of",
        "solid_orientation",
    ],
    &[],
    &["cluster_moment"],
);
const fn post(
    name: &'static str,
    reads: &'static [&'static str],
    writes: &'static [&'static str],
    accumulates: &'static [&'static str],
) -> PassSpec {
    PassSpec { name, module: "solid", stage: Stage::PostStep, reads, writes, accumulates, tolerance: 1e-5 }
}
/// Each membership's signed rotation or logarithm. A logarithm of a turn of a
/// few microradians agrees with the CPU's to the rounding of the quaternions it
/// is taken from (6e-8), a thousandth of it.
pub static TURN: PassSpec = PassSpec {
    tolerance: 2e-3,
    ..post(
        "solid.orient_turn",
        &["cluster_rotation", "solid_clusters_segment", "solid_clusters_member", "slot_of", "solid_orientation_before"],
        &["solid_clusters_turn"],
        &[],
    )
};
/// Each particle's sum of turns.
pub static TURN_SUMS: PassSpec = post(
    "solid.orient_sum",
    &[
        "solid_clusters_first",
        "solid_clusters_count",
        "solid_clusters_order",
        "solid_clusters_live",
        "id",
        "solid_clusters_turn",
    ],
    &["solid_turn_sum"],
    &[],
);
/// Each particle's new orientation and angular velocity. The angular velocity
/// is the angle between two orientations over dt: the GPU's agrees to the
/// rounding of the orientations (1e-7 rad) over dt, a large fraction of it where
/// the turn is a few roundings (the pass run alone, from another step's turns).
pub static UPDATE: PassSpec = PassSpec {
    tolerance: 0.1,
    ..post(
        "solid.orient_update",
        &["solid_turn_sum", "solid_orientation_before", "id", "solid_clusters_count"],
        &["solid_orientation", "solid_spin"],
        &[],
    )
};

/// The rotation by the angle `|w| dt` about `w` (identity below 1e-9 rad/s).
pub fn turn(w: Vec3, dt: f32) -> Quat {
    let speed = w.length();
    if speed < 1e-9 {
        return Quat::IDENTITY;
    }
    let half = 0.5 * speed * dt;
    let axis = w / speed * half.sin();
    Quat::from_xyzw(axis.x, axis.y, axis.z, half.cos())
}

/// The logarithm of a unit quaternion with `w >= 0`: half its rotation vector.
pub fn log(q: Quat) -> Vec3 {
    let v = Vec3::new(q.x, q.y, q.z);
    let s = v.length();
    if s < 1e-9 { v } else { v / s * s.atan2(q.w) }
}

/// The unit quaternion whose logarithm is `v`.
pub fn exp(v: Vec3) -> Quat {
    let theta = v.length();
    if theta < 1e-9 {
        return Quat::from_xyzw(v.x, v.y, v.z, 1.0).normalize();
    }
    let axis = v / theta * theta.sin();
    Quat::from_xyzw(axis.x, axis.y, axis.z, theta.cos())
}

/// `q` or `-q`, the one with `w >= 0` (the same rotation, the short way).
pub fn short(q: Quat) -> Quat {
    if q.w < 0.0 { -q } else { q }
}

/// The angular velocity (rad/s) that turns `before` into `after` in `dt`, the
/// short way (eq. 2.30; none below 1e-9 rad).
pub fn spin(after: Quat, before: Quat, dt: f32) -> Vec3 {
    let r = short(after * before.conjugate());
    let v = Vec3::new(r.x, r.y, r.z);
    let s = v.length();
    let angle = 2.0 * s.atan2(r.w);
    if angle < 1e-9 || dt <= 0.0 { Vec3::ZERO } else { v / s * (angle / dt) }
}

/// A cluster's rotation `r` with the sign that puts it on the side of a member's
/// previous orientation `b` (QLERP, eq. 2.37).
pub fn signed(r: Quat, b: Quat) -> Quat {
    if r.dot(b) < 0.0 { -r } else { r }
}

/// The logarithm of the turn from a member's previous orientation `b` to its
/// cluster's rotation `r`, the short way (ExpMap, eq. 2.38).
pub fn log_turn(r: Quat, b: Quat) -> Vec3 {
    log(short(r * b.conjugate()))
}

/// The ellipsoid's moment `R D`, `D = diag(a^2, b^2, c^2) / 5` (m^2, unit mass).
pub fn ellipsoid(q: Quat, d: Vec3) -> Mat3 {
    let r = Mat3::from_quat(q);
    Mat3::from_cols(r.x_axis * d.x, r.y_axis * d.y, r.z_axis * d.z)
}

/// Prediction: `q = turn(w dt) q`, the orientation before kept.
#[derive(Debug)]
pub struct Predict;

impl CpuPass for Predict {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let dt = cx.dt;
        let a = &mut *cx.attrs;
        let (hq, hb) = (a.handle::<Quat>(ORIENTATION.name), a.handle::<Quat>(BEFORE.name));
        let (mut q, mut before) = (a.take(hq), a.take(hb));
        let w = a.get(a.handle::<Vec3>(SPIN.name));
        q.par_iter_mut().zip(before.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (q, b))| {
            *b = *q;
            *q = (turn(w[i], dt) * *q).normalize();
        });
        a.put(hq, q);
        a.put(hb, before);
    }
}

/// Per cluster: adds its live members' ellipsoid moments to its moment.
#[derive(Debug)]
pub struct Ellipsoid;

impl CpuPass for Ellipsoid {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let d = cx.model.consts::<SolidConsts>().ellipsoid;
        let a = &mut *cx.attrs;
        let h = a.handle::<Mat3>(CLUSTER_MOMENT.name);
        let mut moment = a.take(h);
        let start = a.get(a.handle::<u32>(CLUSTERS.start.name));
        let len = a.get(a.handle::<u32>(CLUSTERS.len.name));
        let live = a.get(a.handle::<u32>(CLUSTERS.live.name));
        let member = a.get(a.handle::<u32>(CLUSTERS.member.name));
        let slot = a.get(a.handle::<u32>("slot_of"));
        let q = a.get(a.handle::<Quat>(ORIENTATION.name));
        moment.par_iter_mut().enumerate().with_min_len(1024).for_each(|(s, m)| {
            let first = start[s] as usize;
            for k in (first..first + len[s] as usize).filter(|&k| live[k] != 0) {
                *m += ellipsoid(q[slot[member[k] as usize] as usize], d);
            }
        });
        a.put(h, moment);
    }
}

/// Per membership: its cluster's rotation with the sign that puts it on the
/// member's previous orientation's side (eq. 2.37), or (ExpMap) the logarithm of
/// its turn from that orientation, taken the short way, with w = 1 (summed over a
/// particle's live memberships, the count its mean divides by).
#[derive(Debug)]
pub struct Turn;

impl CpuPass for Turn {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let blend = cx.model.consts::<SolidConsts>().blend;
        let a = &mut *cx.attrs;
        let h = a.handle::<Quat>(MEMBER_TURN.name);
        let mut out = a.take(h);
        let rotation = a.get(a.handle::<Quat>(ROTATION.name));
        let segment = a.get(a.handle::<u32>(CLUSTERS.segment.name));
        let member = a.get(a.handle::<u32>(CLUSTERS.member.name));
        let slot = a.get(a.handle::<u32>("slot_of"));
        let before = a.get(a.handle::<Quat>(BEFORE.name));
        out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(k, t)| {
            let (r, b) = (rotation[segment[k] as usize], before[slot[member[k] as usize] as usize]);
            *t = match blend {
                Blend::Qlerp => signed(r, b),
                // The w of 1 counts the live memberships in the particle's sum.
                Blend::ExpMap => {
                    let v = log_turn(r, b);
                    Quat::from_xyzw(v.x, v.y, v.z, 1.0)
                }
            };
        });
        a.put(h, out);
    }
}

/// Per particle of a body: the blend of its turns over its live clusters is its
/// orientation (ExpMap's mean divides by their number, the sum's w), and the turn
/// from the one before its angular velocity; a particle in no live cluster (melted)
/// keeps its orientation and stops turning.
#[derive(Debug)]
pub struct Update;

impl CpuPass for Update {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (blend, dt) = (cx.model.consts::<SolidConsts>().blend, cx.dt);
        let a = &mut *cx.attrs;
        let (hq, hw) = (a.handle::<Quat>(ORIENTATION.name), a.handle::<Vec3>(SPIN.name));
        let (mut q, mut w) = (a.take(hq), a.take(hw));
        let sum = a.get(a.handle::<Quat>(TURN_SUM.name));
        let before = a.get(a.handle::<Quat>(BEFORE.name));
        let id = a.get(a.handle::<u32>("id"));
        let count = a.get(a.handle::<u32>(CLUSTERS.count.name));
        q.par_iter_mut().zip(w.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (q, w))| {
            if count.get(id[i] as usize).copied().unwrap_or(0) == 0 {
                return;
            }
            // A melted particle, in no live cluster, stops turning.
            let s = sum[i];
            let live = match blend {
                Blend::Qlerp => s.length_squared() > 0.0,
                Blend::ExpMap => s.w > 0.0,
            };
            if !live {
                *w = Vec3::ZERO;
                return;
            }
            let blended = match blend {
                Blend::Qlerp => s.normalize(),
                Blend::ExpMap => (exp(Vec3::new(s.x, s.y, s.z) / s.w) * before[i]).normalize(),
            };
            *w = spin(blended, before[i], dt);
            *q = blended;
        });
        a.put(hq, q);
        a.put(hw, w);
    }
}
