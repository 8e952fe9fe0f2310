//! The solid module: elastic bodies by shape matching (Mueller et al. 2005, as the
//! first thesis behind Floe, its eqs. 2.10-2.24 and 2.31). A body is a fluid of
//! the scene (its blocks: boxes, spheres, cylinders or meshes) whose particles
//! are at once SPH fluid (pressure from the scheme, so bodies touch walls,
//! terrain, each other and other fluids through it) and members of overlapping
//! clusters that pull them back to their rest shape:
//!
//! - **Clusters** ([`clusters`]): one per particle, its neighbours of the same
//!   material within `cluster_radius` particle spacings at rest (eq. 2.10), stored
//!   as a core index map (`solid_clusters`) with each membership's rest offset.
//! - **A solve after each drift** (a core position solve, `solid.shape`), each
//!   iteration: the members' positions gathered relative to the cluster's own
//!   particle and summed per cluster (its centre, eq. 2.12), the moment
//!   `A = sum (x - c)(x0 - c0)^T` (eq. 2.14) summed, its rotation by polar
//!   decomposition ([`polar`]), each membership's way to its goal
//!   `g - x = R (x0 - c0) + c - x` (eq. 2.19) and weight, and each particle moved
//!   by `alpha` of the weighted mean of its ways: Jacobi (eq. 2.31), weighted
//!   Jacobi (eqs. 2.33-2.35), or in coloured sweeps Gauss-Seidel (eq. 2.32) and
//!   hybrid ([`spec::ClusterSolver`]). The core turns what the solve moved into
//!   velocity (`v += (x - x_predicted) / dt`, the thesis's `v += alpha (g - x) / dt`).
//!   Iterations and the residual (the largest way, m) are reported with the other
//!   solves.
//!
//! Positions relative to a cluster's own particle keep the ways exact to the
//! rounding of a cluster's size rather than of the absolute positions: a way of
//! 1e-7 m summed from goals in absolute coordinates near 1 m is lost to rounding,
//! and with it the momentum the matching conserves.
//!
//! Masses are equal within a body (one material), so the centres are plain means.
//! Particles are addressed by id through the map, so a scene with elastic bodies
//! cannot also have births or deaths (the map needs `slot_of`).
//!
//! Validation ([`cases`]): docs/validation/cases.md section 8's rest shape, free rigid
//! motion, drop volume, stiffness and solver tables, and orientation.
//!
//! Oriented particles ([`orient`]) are optional.
//!
//! Bodies that melt (the scene has the core's liquid fraction, written by the
//! heat module): each solve starts by letting melted members leave their
//! clusters, members that froze again rejoin ([`passes`]' `LEAVE`, `REJOIN`),
//! and counting each cluster's live members and their rest centre (`LIVE`, in
//! every scene); a member's move is blended by `1 - beta` (docs/ice.md).

pub mod cases;
pub mod clusters;
mod consts;
pub mod cpu;
pub mod melting;
pub mod orient;
pub mod passes;
pub mod polar;
pub mod presets;
pub mod spec;
pub mod stability;
mod validate;

pub use consts::SolidConsts;
use consts::{RADIUS_SLACK, consts};
pub use passes::*;

use crate::attrs::{Column, PARTICLES};
use crate::channels::{ChannelSpec, Source};
use crate::maps::cpu::{MemberSum, SegmentSum};
use crate::math::{Mat3, Quat, Real, Vec3};
use crate::model::{BuildError, Model, ModelBuilder};
use crate::module::{BenchCase, BenchKind, BenchSize, ModuleDef, Section};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
use crate::scheme::{Iterate, Op, ReduceOp, Reduction};

/// The module's definition.
pub static MODULE: ModuleDef = ModuleDef {
    id: "solid",
    about: "Elastic solids: fluids whose particles are held to their rest shape by overlapping shape-matching clusters.",
    requires: &["fluid"],
    section: Some(Section { def: SectionDef::of::<spec::Solid>(SECTION), missing: Some("is required") }),
    validate: validate::validate,
    count,
    materials: |_| 0,
    claims: |_| Vec::new(),
    particles: |_, _| Ok(()),
    build,
    retune,
    tunables: TUNABLES,
    cpu: &[
        ("solid.leave", &cpu::Leave),
        ("solid.rejoin", &cpu::Rejoin),
        ("solid.live", &cpu::Live),
        ("solid.gather", &cpu::GatherRelative),
        ("solid.centre_sum", &SegmentSum::<Vec3>::new(&CLUSTERS, "solid_clusters_x", "cluster_x_sum")),
        ("solid.moment", &cpu::Moment),
        ("solid.moment_sum", &SegmentSum::<Mat3>::new(&CLUSTERS, "solid_clusters_moment", "cluster_moment")),
        ("solid.rotate", &cpu::Rotate),
        ("solid.way", &cpu::Way),
        ("solid.deformation_sum", &SegmentSum::<Real>::new(&CLUSTERS, "solid_clusters_weight", "cluster_deformation")),
        ("solid.weigh", &cpu::Weigh),
        ("solid.stiffen", &cpu::Stiffen),
        ("solid.way_sum", &MemberSum::<Vec3>::new(&CLUSTERS, "solid_clusters_way", "solid_way_sum")),
        ("solid.weight_sum", &MemberSum::<Real>::new(&CLUSTERS, "solid_clusters_weight", "solid_weight_sum")),
        ("solid.project", &cpu::Project),
        ("solid.orient_predict", &orient::Predict),
        ("solid.ellipsoid", &orient::Ellipsoid),
        ("solid.orient_turn", &orient::Turn),
        ("solid.orient_sum", &MemberSum::<Quat>::new(&CLUSTERS, "solid_clusters_turn", "solid_turn_sum")),
        ("solid.orient_update", &orient::Update),
        ("solid.motion", &cpu::Motion),
        ("solid.velocity_sum", &SegmentSum::<Vec3>::new(&CLUSTERS, "solid_clusters_v", "cluster_v_sum")),
        ("solid.spin", &cpu::Spin),
        ("solid.spin_sum", &SegmentSum::<Vec3>::new(&CLUSTERS, "solid_clusters_spin", "cluster_spin")),
        ("solid.inertia_sum", &SegmentSum::<Mat3>::new(&CLUSTERS, "solid_clusters_inertia", "cluster_inertia")),
        ("solid.rigid", &cpu::Rigid),
        ("solid.rigid_way", &cpu::RigidWay),
        ("solid.damp", &cpu::Damp),
    ],
    presets: presets::PRESETS,
    dt_limit: |_| None,
    measures: |_| Vec::new(),
    cases: cases::CASES,
    stability: stability::STABILITY,
    bench: &[
        BenchCase {
            name: "solid",
            about: "The elastic_drop jelly scaled to --particles, simulated for --until seconds: the shape matching's cost per step by pass",
            kind: BenchKind::Run { preset: "elastic_drop", measures: &[], size: BenchSize::Particles },
        },
        BenchCase {
            name: "bunny",
            about: "The elastic Stanford bunny (6,537 particles at 1 cm; --particles rescales the spacing) dropped on the floor, simulated for --until seconds",
            kind: BenchKind::Run { preset: "bunny", measures: &[], size: BenchSize::Particles },
        },
        BenchCase {
            name: "ice",
            about: "The melting ice bunny of ice_melting (17,037 particles at 1 cm, 6,537 of ice; --particles rescales the spacing), simulated for --until seconds: the fluid, the heat with its phase change and the shape matching with its blend, by pass",
            kind: BenchKind::Run {
                preset: "ice_melting",
                measures: &["heat.solid_mass", "heat.melt_mass"],
                size: BenchSize::Particles,
            },
        },
    ],
};

/// The module's section of a scene.
pub const SECTION: &str = "solid";

/// Iterations of the iterative rotation extraction per cluster solve.
pub const POLAR_ITERATIONS: u32 = 8;

/// How far each particle is from its rest shape (a channel of the particle set).
pub const DEFORMATION_CHANNEL: ChannelSpec = ChannelSpec {
    name: "deformation",
    unit: "m",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "solid",
    about: "The way from an elastic particle to the mean of its clusters' goals in the step's last iteration: how far the body is from its rest shape there (0 for other particles).",
    source: Source::Attr("solid_residual"),
};

/// Each oriented particle's orientation (a channel of the particle set).
pub const ORIENTATION_CHANNEL: ChannelSpec = ChannelSpec {
    name: "orientation",
    unit: "",
    components: 4,
    exact: false,
    set: PARTICLES,
    module: "solid",
    about: "An oriented particle's rotation from rest, a unit quaternion x, y, z, w (the identity for other particles).",
    source: Source::Attr("solid_orientation"),
};

/// The module's live settings.
pub const TUNABLES: &[Tunable] = &[
    Tunable {
        path: "solid.stiffness",
        unit: "",
        min: Some(0.0),
        max: Some(1.0),
        about: "Shape matching's stiffness alpha: 0 none, 1 rigid within a step.",
        module: "solid",
    },
    Tunable {
        path: "solid.damping",
        unit: "",
        min: Some(0.0),
        max: Some(1.0),
        about: "Share of each cluster's non-rigid velocity removed after each step's solve: 0 none, 1 every cluster moves rigidly.",
        module: "solid",
    },
    Tunable {
        path: "solid.shares",
        unit: "",
        min: None,
        max: None,
        about: "How a jacobi iteration shares each cluster's ways: conserving (momentum conserved) or mean (the thesis's eq. 2.31).",
        module: "solid",
    },
    Tunable {
        path: "solid.iterations",
        unit: "",
        min: Some(1.0),
        max: Some(MAX_ITERATIONS as f64),
        about: "Iterations of the cluster solve per step.",
        module: "solid",
    },
    Tunable {
        path: "solid.solver",
        unit: "",
        min: None,
        max: None,
        about: "Cluster solver: jacobi, weighted_jacobi, gauss_seidel or hybrid.",
        module: "solid",
    },
    Tunable {
        path: "solid.rotation",
        unit: "",
        min: None,
        max: None,
        about: "Rotation extraction: iterative or eigen.",
        module: "solid",
    },
    Tunable {
        path: "solid.oriented.blend",
        unit: "",
        min: None,
        max: None,
        about: "How oriented particles blend their clusters' rotations: qlerp or exp_map (scenes with oriented particles).",
        module: "solid",
    },
];

/// The most iterations a step may run.
pub const MAX_ITERATIONS: u32 = 100;
/// The most colours of the hybrid solver.
pub const MAX_COLOURS: u32 = 64;
/// The fewest live members a cluster of a melting body keeps; with fewer it
/// dissolves. Four: the fewest points that span a volume.
pub const MIN_MEMBERS: u32 = 4;

fn section(scene: &Scene) -> spec::Solid {
    scene.section(SECTION).expect("the registry builds the solid module only for scenes with its section")
}

/// The position solve: a fixed number of iterations, as the thesis's solvers run.
fn shape_solve(iterations: u32, c: &SolidConsts) -> Iterate {
    Iterate {
        name: "solid.shape",
        start: match (c.oriented, c.melting) {
            (true, true) => START_ORIENTED_MELTING,
            (true, false) => START_ORIENTED,
            (false, true) => START_MELTING,
            (false, false) => START,
        },
        iteration: match (c.oriented, c.solver == spec::ClusterSolver::WeightedJacobi) {
            (false, false) => ITERATION,
            (false, true) => ITERATION_WEIGHTED,
            (true, false) => ITERATION_ORIENTED,
            (true, true) => ITERATION_ORIENTED_WEIGHTED,
        },
        residual: Reduction { attr: "solid_residual", op: ReduceOp::Max },
        tolerance: f64::INFINITY,
        min: iterations,
        max: iterations,
        check_every: iterations,
        sweeps: c.sweeps,
        max_sweeps: c.colours.max(c.hybrid_colours),
    }
}

/// Alpha once per step, after the shape solve (its residual is the shape solve's).
fn stiffness_solve() -> Iterate {
    once("solid.stiffness", &[Op::Pass("solid.stiffen")], "solid_residual")
}

/// Once after each step's solve, the velocities damped toward the clusters' rigid
/// motions (its residual: the largest speed relative to them, m/s).
fn rigidity_solve() -> Iterate {
    once("solid.rigidity", RIGIDITY, "solid_nonrigid")
}

/// A solve of no iterations: `start` once, its residual the largest of `residual`.
fn once(name: &'static str, start: &'static [Op], residual: &'static str) -> Iterate {
    Iterate {
        name,
        start,
        iteration: &[],
        residual: Reduction { attr: residual, op: ReduceOp::Max },
        tolerance: f64::INFINITY,
        min: 0,
        max: 0,
        check_every: 1,
        sweeps: 1,
        max_sweeps: 1,
    }
}

/// Each cluster's share of its ways under conserving shares: one over the most
/// clusters any of its members belongs to.
fn shares(lists: &[Vec<u32>], particles: usize) -> Vec<Real> {
    let mut count = vec![0u32; particles];
    for &m in lists.iter().flatten() {
        count[m as usize] += 1;
    }
    lists.iter().map(|l| 1.0 / l.iter().map(|&m| count[m as usize]).max().unwrap_or(1).max(1) as Real).collect()
}

/// The clusters cannot be counted before the bodies are placed: a particle has
/// at most the lattice points within the radius as members.
fn count(_: &Scene) -> Vec<(&'static str, u64)> {
    Vec::new()
}

fn build(scene: &Scene, b: &mut ModelBuilder) -> Result<(), BuildError> {
    let s = section(scene);
    let names: Vec<String> = b.materials().iter().map(|m| m.name.clone()).collect();
    let mut elastic = Vec::new();
    for (i, body) in s.bodies.iter().enumerate() {
        let Some(m) = names.iter().position(|n| *n == body.fluid) else {
            return Err(BuildError::Setting(format!(
                "solid.bodies[{i}].fluid: no fluid named {:?} (the scene's: {names:?})",
                body.fluid
            )));
        };
        elastic.push((m as u32, body.angular_velocity));
        b.solidify(m as u32);
    }
    let Some(Column::Vec3(x)) = b.column("x") else { unreachable!("the core allocates positions first") };
    let x = x.clone();
    // (A scene of one material has no material attribute: every particle is of the first.)
    let material = match b.column("material") {
        Some(Column::U32(m)) => m.clone(),
        _ => vec![0; x.len()],
    };
    let ids: Vec<u32> = (0..x.len() as u32).filter(|&i| elastic.iter().any(|e| e.0 == material[i as usize])).collect();
    let radius = s.cluster_radius * scene.particle_spacing * RADIUS_SLACK;
    let centres = match s.centre_spacing {
        Some(d) => clusters::centres(&ids, &x, &material, d * scene.particle_spacing),
        None => ids.clone(),
    };
    let found = clusters::build(&centres, &ids, &x, &material, radius);
    if let Some(k) = found.lists.iter().position(|l| l.len() < 2) {
        return Err(BuildError::Setting(format!(
            "solid.cluster_radius: particle {} has no neighbour within {} spacings; make it larger",
            centres[k], s.cluster_radius
        )));
    }
    let (colour, colours) = clusters::colours(&found.lists);
    spin(b, &x, &material, &elastic);
    b.map(&CLUSTERS, &found.lists);
    b.attr(&REST, Column::Vec3(found.rest));
    b.attr(&OWNER, Column::U32(centres));
    b.attr(&COLOUR, Column::U32(colour));
    b.attr(&SHARE, Column::F32(shares(&found.lists, x.len())));
    for spec in [
        &CLUSTER_LIVE,
        &REST_CENTRE,
        &MEMBER_X,
        &MEMBER_MOMENT,
        &MEMBER_WAY,
        &MEMBER_WEIGHT,
        &DEFORMATION,
        &CLUSTER_SUM,
        &CLUSTER_MOMENT,
        &CENTRE,
        &WAY_SUM,
        &WEIGHT_SUM,
        &RESIDUAL,
        &MEMBER_V,
        &MEMBER_SPIN,
        &MEMBER_INERTIA,
        &CLUSTER_V,
        &CLUSTER_SPIN,
        &CLUSTER_INERTIA,
        &V_MEAN,
        &OMEGA,
        &NONRIGID,
    ] {
        b.zeros(spec);
    }
    let clusters = found.lists.len();
    b.attr(&ROTATION, Column::Quat(vec![Quat::IDENTITY; clusters]));
    let melting = b.column(crate::quantities::LIQUID_FRACTION.name).is_some();
    if melting {
        b.pass(&LEAVE);
        b.pass(&REJOIN);
    }
    let project = if melting { &PROJECT_BLENDED } else { &PROJECT };
    for pass in [&LIVE, &GATHER, &CENTRE_SUM, &MOMENT, &MOMENT_SUM, &ROTATE, &WAY, &DEFORMATION_SUM, &WEIGH]
        .into_iter()
        .chain([&WAY_SUM_PASS, &WEIGHT_SUM_PASS, project])
    {
        b.pass(pass);
    }
    let mask = elastic.iter().fold(0u32, |m, e| m | 1 << e.0);
    let c = consts(scene, colours, mask, melting);
    if c.oriented {
        orient_particles(b, &material, &elastic);
    }
    b.position_solve(shape_solve(s.iterations, &c));
    if c.stiffness_applied == spec::StiffnessApplied::OncePerStep {
        b.pass(&STIFFEN);
        b.position_solve(stiffness_solve());
    }
    let damp = if melting { &DAMP_BLENDED } else { &DAMP };
    for pass in [&MOTION, &VELOCITY_SUM, &SPIN, &SPIN_SUM, &INERTIA_SUM, &RIGID, &RIGID_WAY, damp] {
        b.pass(pass);
    }
    b.after_position_solves(rigidity_solve());
    b.channel(DEFORMATION_CHANNEL);
    if c.oriented {
        b.channel(ORIENTATION_CHANNEL);
    }
    b.set_consts(c);
    Ok(())
}

/// Oriented particles: each at rest orientation, a body's spinning at its angular
/// velocity; the prediction, the ellipsoids and the blend.
fn orient_particles(b: &mut ModelBuilder, material: &[u32], elastic: &[(u32, [f32; 3])]) {
    let spin =
        material.iter().map(|m| elastic.iter().find(|e| e.0 == *m).map_or(Vec3::ZERO, |e| Vec3::from(e.1))).collect();
    b.zeros(&orient::ORIENTATION);
    b.attr(&orient::SPIN, Column::Vec3(spin));
    for spec in [&orient::BEFORE, &orient::MEMBER_TURN, &orient::TURN_SUM] {
        b.zeros(spec);
    }
    for pass in [&orient::PREDICT, &orient::ELLIPSOID, &orient::TURN, &orient::TURN_SUMS, &orient::UPDATE] {
        b.pass(pass);
    }
}

/// Adds each body's angular velocity about its centre to its particles' velocities.
fn spin(b: &mut ModelBuilder, x: &[Vec3], material: &[u32], elastic: &[(u32, [f32; 3])]) {
    let Some(Column::Vec3(v)) = b.column("v") else { unreachable!("the core allocates velocities first") };
    let mut v = v.clone();
    for &(m, omega) in elastic.iter().filter(|e| e.1 != [0.0; 3]) {
        let mine: Vec<usize> = (0..x.len()).filter(|&i| material[i] == m).collect();
        let centre = mine.iter().map(|&i| x[i]).sum::<Vec3>() / mine.len().max(1) as f32;
        for &i in &mine {
            v[i] += Vec3::from(omega).cross(x[i] - centre);
        }
    }
    b.redeclare(&crate::model::core_attrs::V, Column::Vec3(v));
}

/// The stiffness, iterations, solver, rotation and blend may change (oriented
/// particles may not be switched on or off: the tunables' check refuses a
/// `solid.oriented.blend` for a scene without them).
fn retune(scene: &Scene, model: &mut Model) {
    let old = model.consts::<SolidConsts>();
    let c = consts(scene, old.colours, old.elastic, old.melting);
    let solve = shape_solve(section(scene).iterations, &c);
    for s in model.position_solves.iter_mut().filter(|s| s.name == solve.name) {
        *s = solve;
    }
    model.set_consts(c);
}

#[cfg(test)]
mod tests;
