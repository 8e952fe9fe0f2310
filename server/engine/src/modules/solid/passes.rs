//! The solid module's attributes (the clusters' map, its memberships', clusters'
//! and particles' values) and passes, and the order of an iteration's passes.

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::maps::MapSpec;
use crate::plan::PassSpec;
use crate::scheme::Op;

/// The clusters: segments `solid_cluster`, one per particle of an elastic body.
pub static CLUSTERS: MapSpec =
    crate::index_map!("solid_clusters", segments: "solid_cluster", members: PARTICLES, module: "solid");

const fn attr(name: &'static str, elem: Elem, unit: &'static str, role: Role, space: &'static str) -> AttrSpec {
    AttrSpec { name, elem, unit, role, added_later: false, space, module: "solid", about: name }
}

/// Each membership's rest offset from its cluster's centre (m): state, since a
/// member of a melting body that froze again rejoins at a new offset (saved from
/// the version that added melting on; older snapshots restore it as built).
pub static REST: AttrSpec =
    AttrSpec { added_later: true, ..attr("solid_clusters_rest", Elem::Vec3, "m", Role::State, "solid_clusters") };
/// Each cluster's own particle (id), the origin its positions are taken from.
pub static OWNER: AttrSpec = attr("cluster_owner", Elem::U32, "", Role::Constant, "solid_cluster");
/// Each cluster's colour: no two clusters of a colour share a particle.
pub static COLOUR: AttrSpec = attr("cluster_colour", Elem::U32, "", Role::Constant, "solid_cluster");
/// Each membership's member position relative to its cluster's own particle (m).
pub static MEMBER_X: AttrSpec = attr("solid_clusters_x", Elem::Vec3, "m", Role::Derived, "solid_clusters");
/// Each membership's moment `(x - c) q^T` (m^2).
pub static MEMBER_MOMENT: AttrSpec = attr("solid_clusters_moment", Elem::Mat3, "m^2", Role::Derived, "solid_clusters");
/// Each membership's way to its goal, `g - x`, times its weight (m).
pub static MEMBER_WAY: AttrSpec = attr("solid_clusters_way", Elem::Vec3, "m", Role::Derived, "solid_clusters");
/// Each membership's weight in its member's move (0 for a cluster not swept now).
pub static MEMBER_WEIGHT: AttrSpec = attr("solid_clusters_weight", Elem::F32, "", Role::Derived, "solid_clusters");
/// Each cluster's sum of its members' relative positions (m).
pub static CLUSTER_SUM: AttrSpec = attr("cluster_x_sum", Elem::Vec3, "m", Role::Derived, "solid_cluster");
/// Each cluster's moment matrix `A_pq` (m^2).
pub static CLUSTER_MOMENT: AttrSpec = attr("cluster_moment", Elem::Mat3, "m^2", Role::Derived, "solid_cluster");
/// Each cluster's origin of its goals relative to its own particle (m), and in
/// `w` its share of its ways under [`super::spec::Shares::Conserving`].
pub static CENTRE: AttrSpec = attr("cluster_centre", Elem::Vec4, "m", Role::Derived, "solid_cluster");
/// Each cluster's share of its ways under [`super::spec::Shares::Conserving`]: one
/// over the most clusters any of its members belongs to, so that no particle's
/// shares sum above 1.
pub static SHARE: AttrSpec = attr("cluster_share", Elem::F32, "", Role::Constant, "solid_cluster");
/// Each cluster's rotation from its rest shape (state: the next extraction starts from it).
pub static ROTATION: AttrSpec = attr("cluster_rotation", Elem::Quat, "", Role::State, "solid_cluster");
/// Each cluster's live members: those that have not left it (every member,
/// unless the scene's bodies melt).
pub static CLUSTER_LIVE: AttrSpec = attr("cluster_live", Elem::U32, "", Role::Derived, "solid_cluster");
/// Each cluster's rest offsets' mean over its live members (m): 0 while every
/// member is live in a body that does not melt (the offsets are centred at
/// build); the goals are taken about it.
pub static REST_CENTRE: AttrSpec = attr("cluster_rest_centre", Elem::Vec3, "m", Role::Derived, "solid_cluster");
/// Each cluster's deformation, the summed distance of its live members from their
/// goals, `d_i = sum_j |g_j - x_j|` (m; the first thesis's eq. 2.33): the weight of
/// its goals in its members' means under weighted Jacobi (eq. 2.34).
pub static DEFORMATION: AttrSpec = attr("cluster_deformation", Elem::F32, "m", Role::Derived, "solid_cluster");
/// Each particle's sum of its weighted ways (m).
pub static WAY_SUM: AttrSpec = attr("solid_way_sum", Elem::Vec3, "m", Role::Derived, PARTICLES);
/// Each particle's sum of its ways' weights.
pub static WEIGHT_SUM: AttrSpec = attr("solid_weight_sum", Elem::F32, "", Role::Derived, PARTICLES);
/// Each particle's largest way (its weighted mean) over this iteration's sweeps (m).
pub static RESIDUAL: AttrSpec = attr("solid_residual", Elem::F32, "m", Role::Derived, PARTICLES);
/// Each membership's member velocity (m/s), for the clusters' rigid motion.
pub static MEMBER_V: AttrSpec = attr("solid_clusters_v", Elem::Vec3, "m/s", Role::Derived, "solid_clusters");
/// Each membership's angular momentum about its cluster's centre, `r x v` (m^2/s).
pub static MEMBER_SPIN: AttrSpec = attr("solid_clusters_spin", Elem::Vec3, "m^2/s", Role::Derived, "solid_clusters");
/// Each membership's inertia about its cluster's centre, `|r|^2 1 - r r^T` (m^2).
pub static MEMBER_INERTIA: AttrSpec =
    attr("solid_clusters_inertia", Elem::Mat3, "m^2", Role::Derived, "solid_clusters");
/// Each cluster's sum of its members' velocities (m/s).
pub static CLUSTER_V: AttrSpec = attr("cluster_v_sum", Elem::Vec3, "m/s", Role::Derived, "solid_cluster");
/// Each cluster's angular momentum about its centre, per unit mass (m^2/s).
pub static CLUSTER_SPIN: AttrSpec = attr("cluster_spin", Elem::Vec3, "m^2/s", Role::Derived, "solid_cluster");
/// Each cluster's inertia about its centre, per unit mass (m^2).
pub static CLUSTER_INERTIA: AttrSpec = attr("cluster_inertia", Elem::Mat3, "m^2", Role::Derived, "solid_cluster");
/// Each cluster's rigid motion: the mean velocity of its members (m/s).
pub static V_MEAN: AttrSpec = attr("cluster_v_mean", Elem::Vec3, "m/s", Role::Derived, "solid_cluster");
/// Each cluster's rigid motion: its angular velocity `I^-1 L` (rad/s).
pub static OMEGA: AttrSpec = attr("cluster_omega", Elem::Vec3, "rad/s", Role::Derived, "solid_cluster");
/// Each particle's speed relative to the mean of its clusters' rigid motions before
/// the damping (m/s).
pub static NONRIGID: AttrSpec = attr("solid_nonrigid", Elem::F32, "m/s", Role::Derived, PARTICLES);

const fn solve(
    name: &'static str,
    reads: &'static [&'static str],
    writes: &'static [&'static str],
    accumulates: &'static [&'static str],
) -> PassSpec {
    PassSpec::solve("solid", name, reads, writes, accumulates)
}

pub(super) static GATHER: PassSpec = solve(
    "solid.gather",
    &["solid_clusters_member", "slot_of", "x", "solid_clusters_segment", "cluster_owner", "cluster_colour"],
    &[],
    &["solid_clusters_x"],
);
pub(super) static CENTRE_SUM: PassSpec = solve(
    "solid.centre_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_x"],
    &["cluster_x_sum"],
    &[],
);
/// Members leave the clusters of a melting body: a membership holds (1) while its
/// particle is of an elastic material (a fully melted one is not); one that froze
/// again may rejoin (2, for [`REJOIN`]) where it is within the cluster radius of
/// the cluster's own particle; a cluster with fewer than [`super::MIN_MEMBERS`]
/// members holding or rejoining dissolves (its memberships all leave).
pub(super) static LEAVE: PassSpec = solve(
    "solid.leave",
    &[
        "solid_clusters_start",
        "solid_clusters_len",
        "solid_clusters_member",
        "slot_of",
        "x",
        "material",
        "cluster_owner",
    ],
    &[],
    &["solid_clusters_live"],
);
/// A member rejoining a cluster (2) takes as its rest offset where it was at the
/// end of the last step in the cluster's frame, `R^T (x - o)` with `o` the origin
/// of the cluster's goals: its goal is where it froze, so it joins without a jolt
/// (the original offset pulls melt that flowed and froze back to where it once
/// was in the body: the cube of `ice_cube_in_glass` melted as it fell and frozen
/// by a heat sink over the whole glass halted at 16 m/s).
pub(super) static REJOIN: PassSpec = solve(
    "solid.rejoin",
    &["solid_clusters_x", "solid_clusters_segment", "cluster_rotation", "cluster_centre"],
    &[],
    &["solid_clusters_rest", "solid_clusters_live"],
);
/// Each cluster's live members and their rest offsets' mean.
pub(super) static LIVE: PassSpec = solve(
    "solid.live",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_rest"],
    &["cluster_live", "cluster_rest_centre"],
    &[],
);
pub(super) static MOMENT: PassSpec = solve(
    "solid.moment",
    &[
        "solid_clusters_x",
        "cluster_x_sum",
        "solid_clusters_segment",
        "cluster_live",
        "solid_clusters_rest",
        "cluster_colour",
    ],
    &[],
    &["solid_clusters_moment"],
);
pub(super) static MOMENT_SUM: PassSpec = solve(
    "solid.moment_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_moment"],
    &["cluster_moment"],
    &[],
);
pub(super) static ROTATE: PassSpec = solve(
    "solid.rotate",
    &["cluster_moment", "cluster_x_sum", "cluster_live", "cluster_rest_centre", "cluster_colour", "cluster_share"],
    &["cluster_centre"],
    &["cluster_rotation"],
);
/// A way is the difference of two offsets of a cluster's size (cm) and may be
/// a millionth of them: the GPU's agrees to the rounding of the offsets, a
/// fraction of the way itself.
pub(super) static WAY: PassSpec = PassSpec {
    tolerance: 0.25,
    ..solve(
        "solid.way",
        &[
            "cluster_rotation",
            "cluster_centre",
            "cluster_colour",
            "solid_clusters_segment",
            "solid_clusters_rest",
            "solid_clusters_x",
        ],
        &["solid_clusters_way", "solid_clusters_weight"],
        &[],
    )
};
pub(super) static DEFORMATION_SUM: PassSpec = solve(
    "solid.deformation_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_weight"],
    &["cluster_deformation"],
    &[],
);
/// Weighted Jacobi's weights: each membership's way and weight by its cluster's
/// deformation.
pub(super) static WEIGH: PassSpec = solve(
    "solid.weigh",
    &["cluster_deformation", "solid_clusters_segment"],
    &[],
    &["solid_clusters_way", "solid_clusters_weight"],
);
/// Alpha once per step: each elastic particle's move over the shape solve scaled
/// by alpha.
pub(super) static STIFFEN: PassSpec = solve("solid.stiffen", &["x_predicted"], &[], &["x"]);
pub(super) static WAY_SUM_PASS: PassSpec = solve(
    "solid.way_sum",
    &[
        "solid_clusters_first",
        "solid_clusters_count",
        "solid_clusters_order",
        "solid_clusters_live",
        "id",
        "solid_clusters_way",
    ],
    &["solid_way_sum"],
    &[],
);
pub(super) static WEIGHT_SUM_PASS: PassSpec = solve(
    "solid.weight_sum",
    &[
        "solid_clusters_first",
        "solid_clusters_count",
        "solid_clusters_order",
        "solid_clusters_live",
        "id",
        "solid_clusters_weight",
    ],
    &["solid_weight_sum"],
    &[],
);
pub(super) static PROJECT: PassSpec =
    solve("solid.project", &["solid_way_sum", "solid_weight_sum"], &[], &["x", "solid_residual"]);
/// The projection where the bodies melt: a particle moves by `1 - beta` of its
/// solid update (the first thesis's eqs. 2.39-2.40).
pub(super) static PROJECT_BLENDED: PassSpec =
    solve("solid.project", &["solid_way_sum", "solid_weight_sum", "liquid_fraction"], &[], &["x", "solid_residual"]);

/// Each membership's member position relative to its cluster's own particle and
/// its velocity, for every cluster (the rigid motion's gather).
pub(super) static MOTION: PassSpec = solve(
    "solid.motion",
    &["solid_clusters_member", "slot_of", "x", "v", "solid_clusters_segment", "cluster_owner"],
    &["solid_clusters_x", "solid_clusters_v"],
    &[],
);
pub(super) static VELOCITY_SUM: PassSpec = solve(
    "solid.velocity_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_v"],
    &["cluster_v_sum"],
    &[],
);
/// Each membership's angular momentum and inertia about its cluster's centre.
pub(super) static SPIN: PassSpec = solve(
    "solid.spin",
    &["solid_clusters_x", "cluster_x_sum", "cluster_live", "solid_clusters_segment", "solid_clusters_v"],
    &["solid_clusters_spin", "solid_clusters_inertia"],
    &[],
);
pub(super) static SPIN_SUM: PassSpec = solve(
    "solid.spin_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_spin"],
    &["cluster_spin"],
    &[],
);
pub(super) static INERTIA_SUM: PassSpec = solve(
    "solid.inertia_sum",
    &["solid_clusters_start", "solid_clusters_len", "solid_clusters_live", "solid_clusters_inertia"],
    &["cluster_inertia"],
    &[],
);
/// Each cluster's rigid motion: its members' mean velocity and its angular
/// velocity.
pub(super) static RIGID: PassSpec = solve(
    "solid.rigid",
    &["cluster_v_sum", "cluster_live", "cluster_spin", "cluster_inertia"],
    &["cluster_v_mean", "cluster_omega"],
    &[],
);
/// Each membership's velocity under its cluster's rigid motion (weight 1).
pub(super) static RIGID_WAY: PassSpec = solve(
    "solid.rigid_way",
    &["solid_clusters_x", "cluster_x_sum", "cluster_live", "solid_clusters_segment", "cluster_v_mean", "cluster_omega"],
    &["solid_clusters_way", "solid_clusters_weight"],
    &[],
);
/// Each particle's velocity moves by `damping` of the way to the mean of its
/// clusters' rigid velocities.
pub(super) static DAMP: PassSpec =
    solve("solid.damp", &["solid_way_sum", "solid_weight_sum"], &["solid_nonrigid"], &["v"]);
/// The same where the bodies melt: times `1 - beta`.
pub(super) static DAMP_BLENDED: PassSpec =
    solve("solid.damp", &["solid_way_sum", "solid_weight_sum", "liquid_fraction"], &["solid_nonrigid"], &["v"]);

/// What runs once after the velocities followed the solve: each cluster's rigid
/// motion, and each particle's velocity damped toward the mean of its clusters'.
pub(super) const RIGIDITY: &[Op] = &[
    Op::Pass("solid.motion"),
    Op::Pass("solid.centre_sum"),
    Op::Pass("solid.velocity_sum"),
    Op::Pass("solid.spin"),
    Op::Pass("solid.spin_sum"),
    Op::Pass("solid.inertia_sum"),
    Op::Pass("solid.rigid"),
    Op::Pass("solid.rigid_way"),
    Op::Pass("solid.way_sum"),
    Op::Pass("solid.weight_sum"),
    Op::Pass("solid.damp"),
];

/// What runs once before a step's iterations: the clusters' live members (after
/// the melted leave, where bodies melt), the oriented particles' prediction.
pub(super) const START: &[Op] = &[Op::Pass("solid.live")];
pub(super) const START_MELTING: &[Op] = &[Op::Pass("solid.leave"), Op::Pass("solid.rejoin"), Op::Pass("solid.live")];
pub(super) const START_ORIENTED: &[Op] = &[Op::Pass("solid.orient_predict"), Op::Pass("solid.live")];
pub(super) const START_ORIENTED_MELTING: &[Op] =
    &[Op::Pass("solid.orient_predict"), Op::Pass("solid.leave"), Op::Pass("solid.rejoin"), Op::Pass("solid.live")];

/// The passes of one iteration's sweep, in order, with `$moments` after the
/// moments' sum (the oriented particles' ellipsoids) and `$weights` after the ways
/// (weighted Jacobi's cluster weights).
macro_rules! iteration {
    ([$($moments:literal),*], [$($weights:literal),*]) => {
        &[
            Op::Pass("solid.gather"),
            Op::Pass("solid.centre_sum"),
            Op::Pass("solid.moment"),
            Op::Pass("solid.moment_sum"),
            $(Op::Pass($moments),)*
            Op::Pass("solid.rotate"),
            Op::Pass("solid.way"),
            $(Op::Pass($weights),)*
            Op::Pass("solid.way_sum"),
            Op::Pass("solid.weight_sum"),
            Op::Pass("solid.project"),
        ]
    };
}

/// One iteration's sweep.
pub(super) const ITERATION: &[Op] = iteration!([], []);
/// Under weighted Jacobi: each cluster's goals weighted by its deformation.
pub(super) const ITERATION_WEIGHTED: &[Op] = iteration!([], ["solid.deformation_sum", "solid.weigh"]);
/// With oriented particles: the members' ellipsoids join the moments.
pub(super) const ITERATION_ORIENTED: &[Op] = iteration!(["solid.ellipsoid"], []);
/// Oriented particles under weighted Jacobi.
pub(super) const ITERATION_ORIENTED_WEIGHTED: &[Op] =
    iteration!(["solid.ellipsoid"], ["solid.deformation_sum", "solid.weigh"]);
