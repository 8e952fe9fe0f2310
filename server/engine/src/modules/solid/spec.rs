//! The solid module's scene section (`solid`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Elastic bodies: fluids whose particles are also held to their rest shape by
/// overlapping shape-matching clusters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Solid {
    /// The elastic fluids: each names a fluid of `fluids` (its blocks, boxes or
    /// meshes, are its bodies; blocks of one fluid that touch are one body).
    pub bodies: Vec<Body>,
    /// Radius of a particle's cluster, in particle spacings: its neighbours within
    /// it at rest (the first thesis's eq. 2.10, `d`; default 1.5, about 19 members
    /// on the lattice). Larger clusters overlap more and make the body stiffer.
    #[serde(default = "default_cluster_radius")]
    pub cluster_radius: f32,
    /// Stiffness alpha of the shape matching, 0 (none) to 1 (rigid within a step;
    /// default 0.5). Live.
    #[serde(default = "default_stiffness")]
    pub stiffness: f32,
    /// Iterations of the cluster solve per step (default 3).
    #[serde(default = "default_iterations")]
    pub iterations: u32,
    /// How each cluster's rotation is extracted from its moment matrix `A_pq`.
    #[serde(default)]
    pub rotation: Rotation,
}

/// An elastic fluid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// The fluid's `name`.
    pub fluid: String,
    /// Initial angular velocity about the body's centre of mass (rad/s), added to
    /// its blocks' velocities.
    #[serde(default)]
    pub angular_velocity: [f32; 3],
}

/// The polar decomposition `A = R S` that gives a cluster's rotation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Rotation {
    /// Mueller et al. 2016's robust iterative extraction, warm-started from the
    /// cluster's rotation of the step before (the default: stable through
    /// inversion and flat clusters).
    #[default]
    Iterative,
    /// The first thesis's: `S = sqrt(A^T A)` by eigen-decomposition, `R = A S^-1`,
    /// the smallest axis flipped when `det A < 0`.
    Eigen,
}

fn default_cluster_radius() -> f32 {
    1.5
}

fn default_stiffness() -> f32 {
    0.5
}

fn default_iterations() -> u32 {
    3
}
