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
    /// Cluster centres sampled by Poisson disk (the first thesis's section 2.3.4,
    /// figs. 2.7-2.9): the least distance between two centres, in particle spacings,
    /// 1 to `cluster_radius`. Every particle stays in the body, a member of each
    /// cluster whose centre is within `cluster_radius`; fewer clusters cost less a
    /// step (the matching is O(s m) for s clusters of m members) and, at the same
    /// iterations, hold the body less stiffly. Absent: every particle is a centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_spacing: Option<f32>,
    /// Stiffness alpha of the shape matching, 0 (none) to 1 (rigid within a step;
    /// default 0.5). Live.
    #[serde(default = "default_stiffness")]
    pub stiffness: f32,
    /// When the stiffness applies: each iteration moves the particles by alpha of
    /// their way to their goals (`each_iteration`, the default), or the
    /// iterations move them all the way and alpha is applied once, to the step's
    /// whole move (`once_per_step`: the first thesis's eq. 2.23, `v += alpha (g -
    /// x) / dt`).
    #[serde(default, skip_serializing_if = "StiffnessApplied::is_each_iteration")]
    pub stiffness_applied: StiffnessApplied,
    /// Iterations of the cluster solve per step (default 3). Live.
    #[serde(default = "default_iterations")]
    pub iterations: u32,
    /// How each cluster's rotation is extracted from its moment matrix `A_pq`. Live.
    #[serde(default)]
    pub rotation: Rotation,
    /// How the clusters' goals move the particles in an iteration. Live.
    #[serde(default)]
    pub solver: ClusterSolver,
    /// How a `jacobi` iteration shares a cluster's ways among its members. Live.
    #[serde(default)]
    pub shares: Shares,
    /// The share of each cluster's non-rigid velocity removed after each step's
    /// solve, 0 to 1 (Mueller et al. 2007, "Position based dynamics", section 3.5,
    /// per cluster; default 1: every cluster's members then move as a rigid body
    /// would, each particle taking the mean over its clusters). Live.
    #[serde(default = "default_damping")]
    pub damping: f32,
    /// Colours of the `hybrid` solver (2 to 64; default 2, red-black).
    #[serde(default = "default_colours")]
    pub colours: u32,
    /// Oriented particles (Mueller and Chentanez 2011; the first thesis's eqs.
    /// 2.25-2.30 and 2.36-2.38): each particle an ellipsoid with an orientation
    /// and an angular velocity, whose own moment joins its clusters'. Off when
    /// absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oriented: Option<Oriented>,
}

/// When the shape matching's stiffness alpha applies.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum StiffnessApplied {
    /// Each iteration moves the particles by alpha of their way to their goals.
    #[default]
    EachIteration,
    /// The iterations move the particles to their goals, and the step's whole
    /// move is scaled by alpha once (the first thesis's eq. 2.23).
    OncePerStep,
}

impl StiffnessApplied {
    /// Whether it is the default (scene files may leave it out).
    pub fn is_each_iteration(&self) -> bool {
        *self == StiffnessApplied::EachIteration
    }
}

/// The oriented particles' settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Oriented {
    /// The ellipsoid's radii a, b, c along the particle's own axes, in particle
    /// spacings (default 0.5 each: a ball as wide as the spacing; the thesis takes
    /// a = b = c).
    #[serde(default = "default_radii")]
    pub radii: [f32; 3],
    /// How a particle's orientation is blended from its clusters' rotations.
    #[serde(default)]
    pub blend: Blend,
}

/// Blending a particle's clusters' rotations into its orientation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Blend {
    /// The normalised sum of the rotations, each with the sign that puts it on the
    /// particle's previous orientation's side (eqs. 2.36-2.37; Kavan et al.'s
    /// QLERP).
    #[default]
    Qlerp,
    /// `exp` of the mean of the rotations' logarithms (eq. 2.38; Grassia's
    /// exponential map), the same signs.
    ExpMap,
}

/// The cluster solver: how a particle's goals, one per cluster it belongs to,
/// move it within an iteration (the first thesis's section 2.3.3).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ClusterSolver {
    /// Every cluster from the same positions, each particle moved to the mean of
    /// its goals (eq. 2.31). The default: one sweep an iteration.
    #[default]
    Jacobi,
    /// As `jacobi`, each cluster's goals weighted by the cluster's deformation,
    /// the summed distance of its members from their goals, `d_i = sum_j |g_j -
    /// x_j|`, with `w_i = d_i / sum_k d_k` over the particle's clusters (the first
    /// thesis's eqs. 2.33-2.35): the clusters that deform more count more.
    WeightedJacobi,
    /// Gauss-Seidel (eq. 2.32) as a coloured sweep: the clusters are coloured so
    /// that no two of a colour share a particle, and each colour's clusters match
    /// the positions the colours before them left (the same on both backends: the
    /// CPU does not run the sequential cluster-by-cluster order).
    GaussSeidel,
    /// After Fratarcangeli et al. 2016: the clusters in `colours` colours (the
    /// Gauss-Seidel colour modulo `colours`), Jacobi within a colour (its clusters
    /// may share particles) and Gauss-Seidel across colours. Not sound yet: a
    /// stretched bar does not come back (docs/solid.md, the stiffness table).
    Hybrid,
}

/// How the `jacobi` solver shares each cluster's ways among its members.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Shares {
    /// Each cluster's ways scaled alike for all its members, by one over the most
    /// clusters any of its members belongs to, and summed: a cluster's moves sum to
    /// zero and turn nothing, so the solve conserves linear and angular momentum
    /// (equal masses within a body), and no particle moves further than the mean
    /// of its ways. The default.
    #[default]
    Conserving,
    /// Each particle moved to the mean of its goals (the first thesis's eq. 2.31):
    /// where particles belong to unequal numbers of clusters (a thin feature's
    /// surface) the moves of one cluster's members no longer sum to zero, which
    /// makes momentum (a bunny's ear tips spun up to 30 m/s at DFSPH's step;
    /// docs/solid.md).
    Mean,
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
    /// cluster's rotation of the step before: always a rotation, also through
    /// inversion and for flat clusters, and cheaper, but 8 iterations a solve lag
    /// behind a spinning body (a free spin loses 93 % of its angular momentum in
    /// 10 s, against 1.7 % with `eigen`; `floe validate --case solid_rigid`).
    Iterative,
    /// The first thesis's: `S = sqrt(A^T A)` by eigen-decomposition, `R = A S^-1`,
    /// the smallest axis flipped when `det A < 0`. The default: exact to rounding,
    /// so the matching conserves momentum.
    #[default]
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

fn default_damping() -> f32 {
    1.0
}

fn default_colours() -> u32 {
    2
}

fn default_radii() -> [f32; 3] {
    [0.5; 3]
}
