//! The solid module's constants: what the passes read of the scene's `solid`
//! section and its box, built at the model's build and at each retune.

use super::spec;
use crate::math::{Real, Vec3};
use crate::scene::Scene;

/// The module's constants.
#[derive(Debug, Clone)]
pub struct SolidConsts {
    /// alpha.
    pub stiffness: Real,
    /// When alpha applies.
    pub stiffness_applied: spec::StiffnessApplied,
    /// How rotations are extracted.
    pub rotation: spec::Rotation,
    /// How the goals move the particles.
    pub solver: spec::ClusterSolver,
    /// How a Jacobi iteration shares a cluster's ways.
    pub shares: spec::Shares,
    /// The share of each cluster's non-rigid velocity removed after each step.
    pub damping: Real,
    /// Colours the clusters are swept in: the conflict-free colouring's for
    /// Gauss-Seidel, `colours` for hybrid (a cluster sweeps with its colour
    /// modulo this), 1 for the Jacobi solvers.
    pub sweeps: u32,
    /// Colours of the conflict-free colouring (`cluster_colour`).
    pub colours: u32,
    /// The hybrid solver's colours.
    pub hybrid_colours: u32,
    /// Whether the particles are oriented ([`super::orient`]).
    pub oriented: bool,
    /// The oriented particles' ellipsoid moment `(a^2, b^2, c^2) / 5` (m^2).
    pub ellipsoid: Vec3,
    /// How orientations are blended.
    pub blend: spec::Blend,
    /// The room an elastic particle's centre is held in (m): the scene's box of
    /// walls less half a spacing on each closed face (unbounded on open faces,
    /// and everywhere without a box).
    pub room: (Vec3, Vec3),
    /// The cluster radius (m): a member that froze again rejoins a cluster whose
    /// own particle is within it.
    pub radius: Real,
    /// The elastic materials, a bit each: a member of another material (melted)
    /// leaves its clusters.
    pub elastic: u32,
    /// Whether the bodies melt (the scene has a liquid fraction): their members
    /// leave and their updates blend.
    pub melting: bool,
}

impl SolidConsts {
    /// Whether a Jacobi iteration scales each cluster's ways by its share and sums
    /// them ([`spec::Shares::Conserving`]).
    pub fn conserving(&self) -> bool {
        self.solver == spec::ClusterSolver::Jacobi && self.shares == spec::Shares::Conserving
    }

    /// The share of its way an iteration moves a particle by: alpha, or all of
    /// it where alpha is applied once per step.
    pub fn iteration_alpha(&self) -> Real {
        match self.stiffness_applied {
            spec::StiffnessApplied::EachIteration => self.stiffness,
            spec::StiffnessApplied::OncePerStep => 1.0,
        }
    }

    /// Whether each sweep matches only the clusters of its colour.
    pub fn coloured(&self) -> bool {
        matches!(self.solver, spec::ClusterSolver::GaussSeidel | spec::ClusterSolver::Hybrid)
    }

    /// Whether the cluster of colour `colour` is matched in sweep `sweep`.
    pub fn active(&self, colour: u32, sweep: u32) -> bool {
        !self.coloured() || colour % self.sweeps == sweep
    }

    /// The weight of a cluster not matched in this sweep in its members' means:
    /// 1 for hybrid, whose particle moves by the sum of its colour's ways over
    /// all its clusters (as Jacobi divides), 0 otherwise. Dividing by the colour's
    /// clusters alone gives members of one cluster different shares of its ways
    /// (one particle is in one cluster of a colour, its neighbour in five), which
    /// moves the cluster's centre: momentum made in every sweep, and a stretched
    /// bar that swung wider each time.
    pub fn idle_weight(&self) -> Real {
        if self.solver == spec::ClusterSolver::Hybrid { 1.0 } else { 0.0 }
    }
}

pub(super) fn consts(scene: &Scene, colours: u32, elastic: u32, melting: bool) -> SolidConsts {
    let s = super::section(scene);
    let sweeps = match s.solver {
        spec::ClusterSolver::Jacobi | spec::ClusterSolver::WeightedJacobi => 1,
        spec::ClusterSolver::GaussSeidel => colours,
        spec::ClusterSolver::Hybrid => s.colours,
    };
    let radii = s.oriented.as_ref().map_or([0.0; 3], |o| o.radii);
    SolidConsts {
        stiffness: s.stiffness,
        stiffness_applied: s.stiffness_applied,
        rotation: s.rotation,
        solver: s.solver,
        shares: s.shares,
        damping: s.damping,
        sweeps,
        colours,
        hybrid_colours: s.colours,
        oriented: s.oriented.is_some(),
        ellipsoid: (Vec3::from(radii) * scene.particle_spacing).powf(2.0) / 5.0,
        blend: s.oriented.as_ref().map_or_else(Default::default, |o| o.blend),
        room: room(scene),
        radius: s.cluster_radius * scene.particle_spacing * RADIUS_SLACK,
        elastic,
        melting,
    }
}

/// Lattice neighbours at exactly the cluster radius are members: the radius
/// grows by this factor against the positions' rounding.
pub(super) const RADIUS_SLACK: f32 = 1.0001;

/// The box of walls less half a spacing (a particle's radius) on each closed
/// face: the solve's collision constraint (position-based dynamics, Mueller et
/// al. 2007, alg. 1 line 7). The walls' pressure alone lets a rigid body's corner
/// through: the matching hands the corner the whole body's momentum each step
/// faster than the pressure on that one particle takes it away.
fn room(scene: &Scene) -> (Vec3, Vec3) {
    let r = 0.5 * scene.particle_spacing;
    let mut room = (Vec3::splat(-f32::MAX), Vec3::splat(f32::MAX));
    if let Some(crate::scene::Boundary::Box { min, max, open, .. }) =
        scene.boundaries.iter().find(|b| matches!(b, crate::scene::Boundary::Box { .. }))
    {
        use crate::scene::Face;
        for (k, (low, high)) in [(Face::MinusX, Face::PlusX), (Face::MinusY, Face::PlusY), (Face::MinusZ, Face::PlusZ)]
            .into_iter()
            .enumerate()
        {
            if !open.contains(&low) {
                room.0[k] = min[k] + r;
            }
            if !open.contains(&high) {
                room.1[k] = max[k] - r;
            }
        }
    }
    room
}
