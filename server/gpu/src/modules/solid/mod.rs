//! The solid module on the GPU: the core's generic map kernels gather and sum over
//! the clusters; four kernels of the module's own (a thread per membership, per
//! cluster or per particle, no atomics) do the moments, the rotations, the goals and
//! the Jacobi projection; the uniform `solid` holds [`SolidConsts`] and the counts.

use crate::pass::{GpuPass, always};
use crate::passes::particle_kernel;
use crate::program::Access::{Read as R, ReadWrite as W, Uniform as U};
use floe_engine::attrs::PARTICLES;
use floe_engine::model::Model;
use floe_engine::modules::solid::{CLUSTERS, POLAR_ITERATIONS, SolidConsts, spec::Rotation};

/// Member positions into memberships.
pub static GATHER: GpuPass =
    crate::map_pass!(gather "solid.gather", map "solid_clusters", words 4, from "x" into "solid_clusters_x");
/// Each cluster's sum of positions.
pub static CENTRE_SUM: GpuPass = crate::map_pass!(segment_sum "solid.centre_sum", map "solid_clusters", segments "solid_cluster", words 4, from "solid_clusters_x" into "cluster_x_sum");
/// Each cluster's moment matrix.
pub static MOMENT_SUM: GpuPass = crate::map_pass!(segment_sum "solid.moment_sum", map "solid_clusters", segments "solid_cluster", words 12, from "solid_clusters_moment" into "cluster_moment");
/// Each particle's sum of its goals.
pub static GOAL_SUM: GpuPass = crate::map_pass!(member_sum "solid.goal_sum", map "solid_clusters", members "particles", words 4, from "solid_clusters_goal" into "solid_goal_sum");

/// Each membership's moment.
pub static MOMENT: GpuPass = GpuPass {
    name: "solid.moment",
    source: particle_kernel!("solid.wgsl", "moment.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_clusters_x"),
        (R, "cluster_x_sum"),
        (R, "solid_clusters_segment"),
        (R, "solid_clusters_len"),
        (R, "solid_clusters_rest"),
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
        (R, "cluster_moment"),
        (R, "cluster_x_sum"),
        (R, "solid_clusters_len"),
        (W, "cluster_centre"),
        (W, "cluster_rotation"),
    ],
    space: "solid_cluster",
    when: always,
};

/// Each membership's goal.
pub static GOAL: GpuPass = GpuPass {
    name: "solid.goal",
    source: particle_kernel!("solid.wgsl", "goal.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "cluster_rotation"),
        (R, "cluster_centre"),
        (R, "solid_clusters_segment"),
        (R, "solid_clusters_rest"),
        (W, "solid_clusters_goal"),
    ],
    space: "solid_clusters",
    when: always,
};

/// Each particle's move towards the mean of its goals.
pub static PROJECT: GpuPass = GpuPass {
    name: "solid.project",
    source: particle_kernel!("solid.wgsl", "project.wgsl"),
    entry: "main",
    bindings: &[
        (U, "params"),
        (U, "solid"),
        (R, "solid_goal_sum"),
        (R, "id"),
        (R, "solid_clusters_count"),
        (W, "solid_residual"),
        (W, "x"),
    ],
    space: PARTICLES,
    when: always,
};

/// The uniform's bytes (`Solid` in solid.wgsl), when the scene has elastic bodies.
pub fn uniform(model: &Model) -> Option<Vec<u8>> {
    let c = model.has_module("solid").then(|| model.consts::<SolidConsts>())?;
    let method = match c.rotation {
        Rotation::Iterative => 0,
        Rotation::Eigen => 1,
    };
    let words = [
        c.stiffness.to_bits(),
        0,
        0,
        0,
        model.layout.count(CLUSTERS.segments) as u32,
        model.layout.count(CLUSTERS.name) as u32,
        method,
        POLAR_ITERATIONS,
    ];
    Some(words.iter().flat_map(|w| w.to_le_bytes()).collect())
}
