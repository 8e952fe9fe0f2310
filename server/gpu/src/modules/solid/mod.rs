//! The solid module on the GPU: the core's generic map kernels sum over the
//! clusters; six kernels of the module's own (a thread per membership, per
//! cluster or per particle, no atomics) do the relative gather, the moments, the
//! rotations, the ways, weighted Jacobi's weights and the projection, four more for oriented particles (the
//! prediction, the ellipsoids, the turns and the blend); the uniform `solid` holds
//! [`SolidConsts`] and the counts, the core's `sweep` uniform the colour swept.

use crate::pass::{GpuPass, always};
use crate::passes::particle_kernel;
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use bytemuck::{Pod, Zeroable};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::modules::solid::{
    CLUSTERS, MIN_MEMBERS, POLAR_ITERATIONS, SolidConsts,
    spec::{Blend, ClusterSolver, Rotation},
};

/// Each cluster's sum of relative positions.
pub static CENTRE_SUM: GpuPass = crate::map_pass!(segment_sum "solid.centre_sum", map "solid_clusters", segments "solid_cluster", words 4, from "solid_clusters_x" into "cluster_x_sum");
/// Each cluster's moment matrix.
pub static MOMENT_SUM: GpuPass = crate::map_pass!(segment_sum "solid.moment_sum", map "solid_clusters", segments "solid_cluster", words 12, from "solid_clusters_moment" into "cluster_moment");
/// Each cluster's deformation: its memberships' distances from their goals, summed.
pub static DEFORMATION_SUM: GpuPass = crate::map_pass!(segment_sum "solid.deformation_sum", map "solid_clusters", segments "solid_cluster", words 1, from "solid_clusters_weight" into "cluster_deformation");
/// Each particle's sum of its weighted ways.
pub static WAY_SUM: GpuPass = crate::map_pass!(member_sum "solid.way_sum", map "solid_clusters", members "particles", words 4, from "solid_clusters_way" into "solid_way_sum");
/// Each particle's sum of its ways' weights.
pub static WEIGHT_SUM: GpuPass = crate::map_pass!(member_sum "solid.weight_sum", map "solid_clusters", members "particles", words 1, from "solid_clusters_weight" into "solid_weight_sum");
/// Each cluster's sum of its members' velocities.
pub static VELOCITY_SUM: GpuPass = crate::map_pass!(segment_sum "solid.velocity_sum", map "solid_clusters", segments "solid_cluster", words 4, from "solid_clusters_v" into "cluster_v_sum");
/// Each cluster's angular momentum about its centre.
pub static SPIN_SUM: GpuPass = crate::map_pass!(segment_sum "solid.spin_sum", map "solid_clusters", segments "solid_cluster", words 4, from "solid_clusters_spin" into "cluster_spin");
/// Each cluster's inertia about its centre.
pub static INERTIA_SUM: GpuPass = crate::map_pass!(segment_sum "solid.inertia_sum", map "solid_clusters", segments "solid_cluster", words 12, from "solid_clusters_inertia" into "cluster_inertia");

/// Which members of a melting body's clusters hold.
pub static LEAVE: GpuPass = GpuPass {
    name: "solid.leave",
    source: particle_kernel!("solid.wgsl", "leave.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_start"),
        (R, "solid_clusters_len"),
        (R, "solid_clusters_member"),
        (R, "slot_of"),
        (R, "x"),
        (R, "cluster_owner"),
        (W, "solid_clusters_live"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Each rejoining member's new rest offset.
pub static REJOIN: GpuPass = GpuPass {
    name: "solid.rejoin",
    source: particle_kernel!("solid.wgsl", "rejoin.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_x"),
        (R, "solid_clusters_segment"),
        (R, "cluster_rotation"),
        (R, "cluster_centre"),
        (W, "solid_clusters_rest"),
        (W, "solid_clusters_live"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each cluster's live members and their rest offsets' mean.
pub static LIVE: GpuPass = GpuPass {
    name: "solid.live",
    source: particle_kernel!("solid.wgsl", "live.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_start"),
        (R, "solid_clusters_len"),
        (R, "solid_clusters_live"),
        (R, "solid_clusters_rest"),
        (W, "cluster_live"),
        (W, "cluster_rest_centre"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Member positions relative to their cluster's own particle.
pub static GATHER: GpuPass = GpuPass {
    name: "solid.gather",
    source: particle_kernel!("solid.wgsl", "gather.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "solid_clusters_member"),
        (R, "slot_of"),
        (R, "x"),
        (R, "solid_clusters_segment"),
        (R, "cluster_owner"),
        (R, "cluster_colour"),
        (W, "solid_clusters_x"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each membership's moment.
pub static MOMENT: GpuPass = GpuPass {
    name: "solid.moment",
    source: particle_kernel!("solid.wgsl", "moment.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "solid_clusters_x"),
        (R, "cluster_x_sum"),
        (R, "solid_clusters_segment"),
        (R, "cluster_live"),
        (R, "solid_clusters_rest"),
        (R, "cluster_colour"),
        (W, "solid_clusters_moment"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each cluster's centre and rotation.
pub static ROTATE: GpuPass = GpuPass {
    name: "solid.rotate",
    source: particle_kernel!("solid.wgsl", "rotate.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "cluster_moment"),
        (R, "cluster_x_sum"),
        (R, "cluster_live"),
        (R, "cluster_rest_centre"),
        (R, "cluster_colour"),
        (R, "cluster_share"),
        (W, "cluster_centre"),
        (W, "cluster_rotation"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Each membership's weighted way to its goal and its weight.
pub static WAY: GpuPass = GpuPass {
    name: "solid.way",
    source: particle_kernel!("solid.wgsl", "way.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "cluster_rotation"),
        (R, "cluster_centre"),
        (R, "cluster_colour"),
        (R, "solid_clusters_segment"),
        (R, "solid_clusters_rest"),
        (R, "solid_clusters_x"),
        (W, "solid_clusters_way"),
        (W, "solid_clusters_weight"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Weighted Jacobi's weights: each membership's way and weight by its cluster's deformation.
pub static WEIGH: GpuPass = GpuPass {
    name: "solid.weigh",
    source: particle_kernel!("solid.wgsl", "weigh.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "cluster_deformation"),
        (R, "solid_clusters_segment"),
        (W, "solid_clusters_way"),
        (W, "solid_clusters_weight"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Alpha once per step: each elastic particle's move over the shape solve scaled by alpha.
pub static STIFFEN: GpuPass = GpuPass {
    name: "solid.stiffen",
    source: particle_kernel!("solid.wgsl", "stiffen.wgsl"),
    entry: "main",
    bindings: &[(U, "params"), (U, "solid"), (R, "x_predicted"), (W, "x")],
    space: PARTICLES,
    when: always,
};

/// Each particle's move by the weighted mean of its ways.
pub static PROJECT: GpuPass = GpuPass {
    name: "solid.project",
    source: particle_kernel!("solid.wgsl", "project.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "solid_way_sum"),
        (R, "solid_weight_sum"),
        (W, "x"),
        (W, "solid_residual"),
    ],
    space: PARTICLES,
    when: |m| !melting(m),
};

/// The same where the bodies melt: the move times `1 - beta`.
pub static PROJECT_BLENDED: GpuPass = GpuPass {
    name: "solid.project",
    source: particle_kernel!("solid.wgsl", "project.wgsl", "project_blended.wgsl"),
    entry: "blended",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "sweep"),
        (R, "solid_way_sum"),
        (R, "solid_weight_sum"),
        (W, "x"),
        (W, "solid_residual"),
        (R, "liquid_fraction"),
    ],
    space: PARTICLES,
    when: melting,
};

/// Each membership's relative position and velocity, for every cluster.
pub static MOTION: GpuPass = GpuPass {
    name: "solid.motion",
    source: particle_kernel!("solid.wgsl", "motion.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_member"),
        (R, "slot_of"),
        (R, "x"),
        (R, "v"),
        (R, "solid_clusters_segment"),
        (R, "cluster_owner"),
        (W, "solid_clusters_x"),
        (W, "solid_clusters_v"),
        (U, "dt"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each membership's angular momentum and inertia about its cluster's centre.
pub static SPIN: GpuPass = GpuPass {
    name: "solid.spin",
    source: particle_kernel!("solid.wgsl", "spin.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_x"),
        (R, "cluster_x_sum"),
        (R, "cluster_live"),
        (R, "solid_clusters_segment"),
        (R, "solid_clusters_v"),
        (W, "solid_clusters_spin"),
        (W, "solid_clusters_inertia"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each cluster's rigid motion.
pub static RIGID: GpuPass = GpuPass {
    name: "solid.rigid",
    source: particle_kernel!("solid.wgsl", "rigid.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "cluster_v_sum"),
        (R, "cluster_live"),
        (R, "cluster_spin"),
        (R, "cluster_inertia"),
        (W, "cluster_v_mean"),
        (W, "cluster_omega"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Each membership's velocity under its cluster's rigid motion.
pub static RIGID_WAY: GpuPass = GpuPass {
    name: "solid.rigid_way",
    source: particle_kernel!("solid.wgsl", "rigid_way.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_x"),
        (R, "cluster_x_sum"),
        (R, "cluster_live"),
        (R, "solid_clusters_segment"),
        (R, "cluster_v_mean"),
        (R, "cluster_omega"),
        (W, "solid_clusters_way"),
        (W, "solid_clusters_weight"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each particle's velocity damped toward its clusters' rigid motions.
pub static DAMP: GpuPass = GpuPass {
    name: "solid.damp",
    source: particle_kernel!("solid.wgsl", "damp.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_way_sum"),
        (R, "solid_weight_sum"),
        (W, "solid_nonrigid"),
        (W, "v"),
    ],
    space: PARTICLES,
    when: |m| !melting(m),
};

/// The same where the bodies melt: times `1 - beta`.
pub static DAMP_BLENDED: GpuPass = GpuPass {
    name: "solid.damp",
    source: particle_kernel!("solid.wgsl", "damp.wgsl", "damp_blended.wgsl"),
    entry: "blended",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_way_sum"),
        (R, "solid_weight_sum"),
        (W, "solid_nonrigid"),
        (W, "v"),
        (R, "liquid_fraction"),
    ],
    space: PARTICLES,
    when: melting,
};

/// Whether the scene's bodies melt.
fn melting(model: &Model) -> bool {
    model.consts::<SolidConsts>().melting
}

/// Each particle's sum of turns (oriented particles).
pub static ORIENT_SUM: GpuPass = crate::map_pass!(member_sum "solid.orient_sum", map "solid_clusters", members "particles", words 4, from "solid_clusters_turn" into "solid_turn_sum");

/// The oriented particles' prediction.
pub static ORIENT_PREDICT: GpuPass = GpuPass {
    name: "solid.orient_predict",
    source: particle_kernel!("solid.wgsl", "orient.wgsl", "orient_predict.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "dt"),
        (R, "solid_spin"),
        (W, "solid_orientation_before"),
        (W, "solid_orientation"),
    ],
    space: PARTICLES,
    when: always,
};

/// The members' ellipsoids into their clusters' moments.
pub static ELLIPSOID: GpuPass = GpuPass {
    name: "solid.ellipsoid",
    source: particle_kernel!("solid.wgsl", "ellipsoid.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_start"),
        (R, "solid_clusters_len"),
        (R, "solid_clusters_live"),
        (R, "solid_clusters_member"),
        (R, "slot_of"),
        (R, "solid_orientation"),
        (W, "cluster_moment"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Each membership's signed rotation or logarithm.
pub static ORIENT_TURN: GpuPass = GpuPass {
    name: "solid.orient_turn",
    source: particle_kernel!("solid.wgsl", "orient.wgsl", "orient_turn.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "cluster_rotation"),
        (R, "solid_clusters_segment"),
        (R, "solid_clusters_member"),
        (R, "slot_of"),
        (R, "solid_orientation_before"),
        (W, "solid_clusters_turn"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each particle's blended orientation and angular velocity.
pub static ORIENT_UPDATE: GpuPass = GpuPass {
    name: "solid.orient_update",
    source: particle_kernel!("solid.wgsl", "orient.wgsl", "orient_update.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (U, "dt"),
        (R, "solid_turn_sum"),
        (R, "solid_orientation_before"),
        (R, "id"),
        (R, "solid_clusters_count"),
        (W, "solid_orientation"),
        (W, "solid_spin"),
    ],
    space: PARTICLES,
    when: always,
};

/// The `solid` uniform (`Solid` in solid.wgsl; each field's meaning there).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct SolidParams {
    /// Stiffness alpha; the ellipsoid moment (a^2, b^2, c^2) / 5 (m^2).
    settings: [f32; 4],
    /// Clusters, memberships, rotation method, iterations of the iterative one.
    sizes: [u32; 4],
    /// Solver, colours, blend, the weight of a cluster of another colour.
    solver: [u32; 4],
    /// The room's lower corner (m).
    low: [f32; 4],
    /// The room's upper corner (m).
    high: [f32; 4],
    /// The cluster radius (m, as f32 bits), the elastic materials' bits, MIN_MEMBERS, melting.
    melt: [u32; 4],
    /// The damping toward the rigid motions; 1 under conserving shares, else 0.
    rigid: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<SolidParams>() == 112);

/// The uniform's bytes, when the scene has elastic bodies.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    let c = model.has_module("solid").then(|| model.consts::<SolidConsts>())?;
    let method = match c.rotation {
        Rotation::Iterative => 0,
        Rotation::Eigen => 1,
    };
    let solver = match c.solver {
        ClusterSolver::Jacobi => 0,
        ClusterSolver::WeightedJacobi => 1,
        ClusterSolver::GaussSeidel | ClusterSolver::Hybrid => 2,
    };
    let blend = match c.blend {
        Blend::Qlerp => 0,
        Blend::ExpMap => 1,
    };
    let (low, high) = c.room;
    let u = SolidParams {
        settings: [c.iteration_alpha(), c.ellipsoid.x, c.ellipsoid.y, c.ellipsoid.z],
        sizes: [
            model.layout.count(CLUSTERS.segments) as u32,
            model.layout.count(CLUSTERS.name) as u32,
            method,
            POLAR_ITERATIONS,
        ],
        solver: [solver, c.sweeps, blend, c.idle_weight() as u32],
        low: [low.x, low.y, low.z, 0.0],
        high: [high.x, high.y, high.z, 0.0],
        melt: [c.radius.to_bits(), c.elastic, MIN_MEMBERS, u32::from(c.melting)],
        rigid: [c.damping, f32::from(u8::from(c.conserving())), c.stiffness, 0.0],
    };
    Some(bytemuck::bytes_of(&u).to_vec())
}
