//! The solid module's validation cases (docs/validation/cases.md section 8), on the preset
//! `elastic_drop`'s jelly cube (0.2 m), a bar of it, or the preset `bunny`: the
//! rest shape, free rigid motion, drop volume, solver and stiffness tables,
//! weighted against uniform averaging, and orientation.

use super::{RESIDUAL, orient, polar};
use crate::Simulation;
use crate::attrs::Column;
use crate::math::{Mat3, Quat, Vec3};
use crate::validation::cases::{Case, Measured, Variant};

/// The cases, for the module registry.
pub const CASES: &[Case] = &[
    Case {
        name: "solid_rest",
        module: "solid",
        reference: "docs/validation/cases.md section 8, rest: an unforced solid keeps its rest shape; after 1000 steps the largest distance of a particle from the best rigid transform of its rest shape, relative to the body's size (the reference asks 1e-6)",
        preset: "elastic_drop",
        primary_error: "shape_error",
        spacings: (&[0.04, 0.02], &[0.04, 0.02, 0.01]),
        checked_at: Some(0.04),
        // 1.5e-7 at 4 cm, 2.6e-7 at 2 cm.
        bounds: &[("shape_error", 1e-6)],
        variants: &[Variant { name: "no_gravity", overrides: &["gravity=[0,0,0]"] }],
        measure: rest_case,
    },
    Case {
        name: "solid_rigid",
        module: "solid",
        reference: "docs/validation/cases.md section 8, free rigid motion: alpha = 1, no gravity, the jelly spinning at 2 rad/s about its vertical axis for 10 s (clear of the walls); the drift of its linear momentum relative to the sum of its particles' momenta |m v|, of its angular momentum about its centre relative to its start, and its shape error at the end relative to its size (the reference asks 1e-6, 1e-3 and the rest's)",
        preset: "elastic_drop",
        primary_error: "angular_momentum",
        spacings: (&[0.04], &[0.04, 0.02]),
        checked_at: Some(0.04),
        // At 4 cm: 2.7e-3, 1.8e-2 and 1.9e-6; the reference's 1e-6 and 1e-3 are not met (the
        // f32 positions' rounding: docs/solid.md).
        bounds: &[("linear_momentum", 1e-2), ("angular_momentum", 5e-2), ("shape_error", 1e-5)],
        variants: &[
            Variant { name: "spinning", overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], WCSPH] },
            Variant {
                name: "spinning_dt_2e-4",
                overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], WCSPH, SMALL_STEP],
            },
            Variant { name: "dfsph", overrides: SPINNING },
            Variant {
                name: "iterative",
                overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], WCSPH, "solid.rotation=\"iterative\""],
            },
            Variant {
                name: "gauss_seidel",
                overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], WCSPH, "solid.solver=\"gauss_seidel\""],
            },
        ],
        measure: rigid_case,
    },
    Case {
        name: "solid_drop",
        module: "solid",
        reference: "docs/validation/cases.md section 8, drop: the jelly cube dropped 0.3 m on the floor with alpha = 1 settles with its volume within 1 % of its rest volume; the volume ratio is det F of the whole body's best affine map F = A_pq A_qq^-1 from its rest shape (Mueller et al. 2005, eq. 6), at 2 s",
        preset: "elastic_drop",
        primary_error: "volume_error",
        spacings: (&[0.04, 0.02], &[0.04, 0.02, 0.01]),
        // 2.8e-8 at 4 cm (nearly one cluster), 1.0e-3 at 2 cm.
        checked_at: Some(0.02),
        bounds: &[("volume_error", 1e-2)],
        variants: &[
            Variant { name: "rigid", overrides: &["solid.stiffness=1"] },
            Variant { name: "soft", overrides: &["solid.stiffness=0.5"] },
        ],
        measure: drop_case,
    },
    Case {
        name: "solid_solvers",
        module: "solid",
        reference: "docs/validation/cases.md section 8, solver table (the first thesis compares its solvers on the Stanford bunny at 6525, 2106 and 889 particles): the preset bunny (894, 2100 and 6537 particles at 1.96, 1.46 and 1 cm) stretched by 10 % along x, alpha = 1, each solver iterated on it until the largest way to a particle's goals is at most 1e-4 of the particle spacing (at most 5000 iterations); the iterations and the wall time they took, per solver and resolution",
        preset: "bunny",
        primary_error: "residual",
        spacings: (&[0.0196, 0.0146], &[0.0196, 0.0146, 0.01]),
        checked_at: Some(0.0196),
        bounds: &[("residual", 1e-4)],
        variants: &[
            Variant { name: "jacobi", overrides: &["gravity=[0,0,0]", "solid.stiffness=1", "solid.solver=\"jacobi\""] },
            Variant {
                name: "weighted_jacobi",
                overrides: &["gravity=[0,0,0]", "solid.stiffness=1", "solid.solver=\"weighted_jacobi\""],
            },
            Variant {
                name: "gauss_seidel",
                overrides: &["gravity=[0,0,0]", "solid.stiffness=1", "solid.solver=\"gauss_seidel\""],
            },
            Variant { name: "hybrid", overrides: &["gravity=[0,0,0]", "solid.stiffness=1", "solid.solver=\"hybrid\""] },
        ],
        measure: solver_case,
    },
    Case {
        name: "solid_weighting",
        module: "solid",
        reference: "docs/validation/cases.md section 8, weighted against uniform averaging (the first thesis's comparison over 140 steps): the preset bunny landing on the floor at 1.4 m/s (as dropped from 10 cm), alpha = 0.5, three iterations a step, for 140 steps with uniform (jacobi) and distance-weighted (weighted_jacobi, eqs. 2.33-2.35) averaging of the goals; the mean over the steps of the largest way left after the step's solve and the largest shape error over the steps (both in particle spacings)",
        preset: "bunny",
        primary_error: "mean_residual",
        spacings: (&[0.0196, 0.0146], &[0.0196, 0.0146, 0.01]),
        checked_at: Some(0.0196),
        // Uniform at 1.96 cm: 0.010 and 0.85.
        bounds: &[("mean_residual", 0.05), ("peak_shape_error", 2.0)],
        variants: &[
            Variant {
                name: "uniform",
                overrides: &[
                    LANDING[0],
                    LANDING[1],
                    LANDING[2],
                    WCSPH,
                    "solid.solver=\"jacobi\"",
                    "solid.shares=\"mean\"",
                ],
            },
            Variant {
                name: "weighted",
                overrides: &[LANDING[0], LANDING[1], LANDING[2], WCSPH, "solid.solver=\"weighted_jacobi\""],
            },
        ],
        measure: weighting_case,
    },
    Case {
        name: "solid_orientation",
        module: "solid",
        reference: "docs/validation/cases.md section 8, orientation: oriented particles (Mueller and Chentanez 2011) of the jelly spinning freely at 2 rad/s for 1 s, alpha = 1: the largest departure of a quaternion's length from 1, the largest angle between a particle's orientation and the body's rotation (its best rigid fit), and the largest angle between the QLERP and the ExpMap blends of the same clusters' rotations at the end (the reference asks 1e-6 and 1e-3 rad)",
        preset: "elastic_drop",
        primary_error: "blend_difference",
        spacings: (&[0.04, 0.02], &[0.04, 0.02, 0.01]),
        checked_at: Some(0.04),
        bounds: &[("unit_length", 1e-6), ("orientation_error", 1e-2), ("blend_difference", 1e-3)],
        variants: &[
            Variant { name: "qlerp", overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], "solid.oriented={}"] },
            Variant {
                name: "exp_map",
                overrides: &[SPINNING[0], SPINNING[1], SPINNING[2], "solid.oriented={\"blend\":\"exp_map\"}"],
            },
        ],
        measure: orientation_case,
    },
    Case {
        name: "ice_insulated",
        module: "solid",
        reference: "conservation: the ice cube of ice_cube_in_glass at its melting point melting in water at 293 K in an insulated glass for 1 s: the total heat (sensible and latent) to 1e-6 relative, the solid's mass only falling, solid and melt together the cube's mass; on DFSPH, on WCSPH, and in the first thesis's two configurations (shape matching, oriented particles, each with weighted Jacobi)",
        preset: "ice_cube_in_glass",
        primary_error: "heat_drift",
        spacings: (&[0.01, 0.0075], &[0.01, 0.0075, 0.005]),
        checked_at: Some(0.01),
        bounds: &[("heat_drift", 1e-6), ("solid_mass_rise_kg", 0.0), ("mass_error", 1e-6)],
        variants: &[
            Variant { name: "default", overrides: &["heat.fluids[1].temperature=273.15"] },
            Variant { name: "wcsph", overrides: &["heat.fluids[1].temperature=273.15", "solver.method=\"wcsph\""] },
            // The first thesis's two configurations: shape matching and oriented
            // particles, each with its weighted Jacobi.
            Variant {
                name: "sm_weighted_jacobi",
                overrides: &["heat.fluids[1].temperature=273.15", "solid.solver=\"weighted_jacobi\""],
            },
            Variant {
                name: "op_weighted_jacobi",
                overrides: &[
                    "heat.fluids[1].temperature=273.15",
                    "solid.solver=\"weighted_jacobi\"",
                    "solid.oriented={}",
                ],
            },
        ],
        measure: super::melting::insulated_case,
    },
    Case {
        name: "solid_stiffness",
        module: "solid",
        reference: "docs/validation/cases.md section 8, stiffness table: a bar 0.4 x 0.08 x 0.08 m stretched by 10 % along its length and released without gravity, for 2 s; the period (s) of its length's oscillation and the ratio of two successive peaks of its stretch (0 where it does not swing back: overdamped), for alpha 0.1, 0.5 and 1, a step capped at 2e-4 s, alpha applied once per step (eq. 2.23) rather than each iteration, and each solver; the stretch left at the end relative to the initial one (checked: the bar comes back)",
        preset: "elastic_drop",
        primary_error: "stretch_left",
        spacings: (&[0.02], &[0.02, 0.01]),
        checked_at: Some(0.02),
        bounds: &[("stretch_left", 0.05)],
        variants: &[
            Variant { name: "alpha_0.5", overrides: &[BAR[0], BAR[1], "solid.stiffness=0.5"] },
            Variant { name: "alpha_0.1", overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1"] },
            Variant { name: "alpha_1", overrides: &[BAR[0], BAR[1], "solid.stiffness=1"] },
            Variant { name: "alpha_0.5_dt_2e-4", overrides: &[BAR[0], BAR[1], "solid.stiffness=0.5", SMALL_STEP] },
            Variant { name: "alpha_0.1_dt_2e-4", overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", SMALL_STEP] },
            Variant {
                name: "alpha_0.5_once_per_step",
                overrides: &[BAR[0], BAR[1], "solid.stiffness=0.5", "solid.stiffness_applied=\"once_per_step\""],
            },
            Variant {
                name: "alpha_0.1_once_per_step",
                overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", "solid.stiffness_applied=\"once_per_step\""],
            },
            Variant {
                name: "weighted_jacobi",
                overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", "solid.solver=\"weighted_jacobi\""],
            },
            Variant {
                name: "gauss_seidel",
                overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", "solid.solver=\"gauss_seidel\""],
            },
            Variant { name: "hybrid", overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", "solid.solver=\"hybrid\""] },
            Variant {
                name: "hybrid_3_colours",
                overrides: &[BAR[0], BAR[1], "solid.stiffness=0.1", "solid.solver=\"hybrid\"", "solid.colours=3"],
            },
        ],
        measure: stiffness_case,
    },
];

/// The stiffness table's bar: no gravity, 0.4 x 0.08 x 0.08 m in the box.
const BAR: &[&str] = &["gravity=[0,0,0]", r#"fluids[0].blocks=[{"min":[0.1,0.3,0.26],"max":[0.5,0.38,0.34]}]"#];
/// The stiffness table's smaller step.
const SMALL_STEP: &str = r#"solver.time_step={"mode":"adaptive","max":0.0002}"#;

/// The weighting comparison: the bunny a centimetre above the floor, falling
/// at the speed of a drop from 10 cm.
const LANDING: &[&str] = &[
    r#"fluids[0].blocks[0].min=[0.24,0.01,0.18]"#,
    r#"fluids[0].blocks[0].max=[0.56,0.322,0.4235]"#,
    "fluids[0].blocks[0].velocity=[0,-1.4,0]",
];

/// WCSPH's acoustic step, which two cases keep (the presets step on DFSPH):
/// `solid_rigid`, whose free spin loses angular momentum at the rate of the
/// position-based update on the flow's step (each step's straight prediction
/// turns the body by `atan(omega dt)` and the chord back is shorter than the arc:
/// 0.15 of it in 10 s at DFSPH's 5 ms, its `dfsph` variant), and
/// `solid_weighting`, the thesis's comparison over a number of steps.
const WCSPH: &str = "solver.method=\"wcsph\"";

/// The free rigid motion: no gravity, alpha 1, 2 rad/s about the vertical.
const SPINNING: &[&str] = &["gravity=[0,0,0]", "solid.stiffness=1", "solid.bodies[0].angular_velocity=[0,2,0]"];

/// Positions by particle id.
pub fn by_id(sim: &Simulation) -> Vec<Vec3> {
    vec3s_by_id(sim, "x")
}

/// A vector attribute of the particles by particle id.
fn vec3s_by_id(sim: &Simulation, name: &str) -> Vec<Vec3> {
    let cols = sim.backend().download(&[name, "id"]);
    let (Column::Vec3(x), Column::U32(id)) = (&cols[0], &cols[1]) else { panic!("{name} and ids") };
    let mut out = vec![Vec3::ZERO; x.len()];
    for (p, &i) in x.iter().zip(id) {
        out[i as usize] = *p;
    }
    out
}

/// Steps while `more` (asked before each step and after the last) says so: the
/// steps' wall time (s), or what a run that halted measured.
fn run(sim: &mut Simulation, mut more: impl FnMut(&Simulation) -> bool) -> Result<f64, Measured> {
    let mut wall = 0.0;
    while more(sim) {
        let t = std::time::Instant::now();
        if let Err(h) = sim.step() {
            return Err((wall, Some(h), Vec::new()));
        }
        wall += t.elapsed().as_secs_f64();
    }
    Ok(wall)
}

/// The largest distance (m) of a particle from the best rigid motion of its rest
/// positions `x0` onto `x` (the whole body's shape matching).
pub fn shape_error(x0: &[Vec3], x: &[Vec3]) -> f32 {
    let n = x.len() as f32;
    let (c0, c) = (x0.iter().sum::<Vec3>() / n, x.iter().sum::<Vec3>() / n);
    let a = x0.iter().zip(x).fold(Mat3::ZERO, |a, (&p0, &p)| {
        let (q, r) = (p0 - c0, p - c);
        a + Mat3::from_cols(r * q.x, r * q.y, r * q.z)
    });
    let rot = polar::eigen(a);
    x0.iter().zip(x).map(|(&p0, &p)| (rot * (p0 - c0) + c - p).length()).fold(0.0, f32::max)
}

/// 1000 steps at rest; the shape error relative to the cube's side.
fn rest_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let x0 = by_id(sim);
    let mut steps = 0;
    let wall = match run(sim, |_| {
        steps += 1;
        steps <= 1000
    }) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    let e = shape_error(&x0, &by_id(sim)) / super::presets::DROP.0;
    (wall, None, vec![("shape_error", f64::from(e))])
}

/// Linear momentum and angular momentum about the centre (equal masses: per unit
/// particle mass), in f64.
fn momenta(x: &[Vec3], v: &[Vec3]) -> (glam::DVec3, glam::DVec3) {
    let n = x.len() as f64;
    let c = x.iter().map(|p| p.as_dvec3()).sum::<glam::DVec3>() / n;
    let p = v.iter().map(|u| u.as_dvec3()).sum::<glam::DVec3>();
    let l = x.iter().zip(v).map(|(q, u)| (q.as_dvec3() - c).cross(u.as_dvec3())).sum::<glam::DVec3>();
    (p, l)
}

/// 10 s of free spin: the momenta's drifts and the shape error at the end.
fn rigid_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let x0 = by_id(sim);
    let v0 = vec3s_by_id(sim, "v");
    let (p0, l0) = momenta(&x0, &v0);
    let scale: f64 = v0.iter().map(|u| f64::from(u.length())).sum();
    let wall = match run(sim, |sim| sim.time() < 10.0) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    let x = by_id(sim);
    let (p, l) = momenta(&x, &vec3s_by_id(sim, "v"));
    let e = shape_error(&x0, &x) / super::presets::DROP.0;
    (
        wall,
        None,
        vec![
            ("linear_momentum", (p - p0).length() / scale),
            ("angular_momentum", (l - l0).length() / l0.length()),
            ("shape_error", f64::from(e)),
        ],
    )
}

/// `|det F - 1|` of the whole body's best affine map from its rest shape after
/// 2 s: dropped, bounced and settled on the floor.
fn drop_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let x0 = by_id(sim);
    let wall = match run(sim, |sim| sim.time() < 2.0) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    (wall, None, vec![("volume_error", (volume_ratio(&x0, &by_id(sim)) - 1.0).abs())])
}

/// `det F` of the best affine map `F = A_pq A_qq^-1` taking the rest positions
/// `x0` onto `x` (Mueller et al. 2005, eq. 6, the whole body as one cluster), in
/// f64: the ratio of the volume the body's affine part encloses to its rest
/// volume.
pub fn volume_ratio(x0: &[Vec3], x: &[Vec3]) -> f64 {
    let n = x.len() as f64;
    let centre = |of: &[Vec3]| of.iter().map(|p| p.as_dvec3()).sum::<glam::DVec3>() / n;
    let (c0, c) = (centre(x0), centre(x));
    let outer = |a: glam::DVec3, b: glam::DVec3| glam::DMat3::from_cols(a * b.x, a * b.y, a * b.z);
    let (mut apq, mut aqq) = (glam::DMat3::ZERO, glam::DMat3::ZERO);
    for (p0, p) in x0.iter().zip(x) {
        let (q, r) = (p0.as_dvec3() - c0, p.as_dvec3() - c);
        apq += outer(r, q);
        aqq += outer(q, q);
    }
    (apq * aqq.inverse()).determinant()
}

/// Stretches the body by 10 % along x about its centre.
fn stretch(sim: &mut Simulation) {
    let Column::Vec3(x) = &sim.backend().download(&["x"])[0] else { panic!("positions") };
    let centre = x.iter().sum::<Vec3>() / x.len() as f32;
    let stretched = x.iter().map(|p| *p + Vec3::X * (0.1 * (p.x - centre.x))).collect();
    sim.backend_mut().upload("x", Column::Vec3(stretched));
}

/// The steps of the weighting comparison (the thesis's).
const WEIGHTING_STEPS: u32 = 140;

/// Runs 140 steps and measures the way left after each step's solve and the
/// largest shape error, both in spacings.
fn weighting_case(sim: &mut Simulation, spacing: f64) -> Measured {
    let x0 = by_id(sim);
    let (mut steps, mut ways, mut peak) = (0, 0.0, 0.0f64);
    let wall = match run(sim, |sim| {
        if steps > 0 {
            let Column::F32(r) = &sim.backend().download(&[RESIDUAL.name])[0] else { panic!("residuals") };
            ways += f64::from(r.iter().fold(0.0, |a: f32, &b| a.max(b)));
            peak = peak.max(f64::from(shape_error(&x0, &by_id(sim))));
        }
        steps += 1;
        steps <= WEIGHTING_STEPS
    }) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    let mean = ways / f64::from(WEIGHTING_STEPS) / spacing;
    (wall, None, vec![("mean_residual", mean), ("peak_shape_error", peak / spacing)])
}

/// The most iterations the solver table runs.
const TABLE_ITERATIONS: u32 = 5000;

/// Stretches the body by 10 % along x about its centre, then runs the scene's
/// shape solve alone until its residual is at most 1e-4 spacings: the wall time
/// is the solve's, the iterations a measure.
fn solver_case(sim: &mut Simulation, spacing: f64) -> Measured {
    stretch(sim);
    let tolerance = 1e-4 * spacing;
    let solve = crate::scheme::Iterate {
        tolerance,
        min: 1,
        max: TABLE_ITERATIONS,
        check_every: 1,
        ..sim.model().position_solves[0]
    };
    let t = std::time::Instant::now();
    let done = solve.run(sim.backend_mut(), 1e-3);
    sim.backend_mut().end_step();
    let wall = t.elapsed().as_secs_f64();
    let (iterations, residual) = match done {
        Ok(s) => (s.iterations, s.residual),
        Err(_) => {
            let r = crate::scheme::Reduction { attr: RESIDUAL.name, op: crate::scheme::ReduceOp::Max };
            (TABLE_ITERATIONS, sim.backend_mut().reduce(&r).unwrap_or(f64::NAN))
        }
    };
    (wall, None, vec![("residual", residual / spacing), ("iterations", f64::from(iterations))])
}

/// The angle (rad) of the rotation between two unit quaternions.
fn angle_between(a: Quat, b: Quat) -> f64 {
    let r = orient::short(a * b.conjugate());
    2.0 * f64::from(Vec3::new(r.x, r.y, r.z).length()).atan2(f64::from(r.w))
}

/// 1 s of free spin with oriented particles, then the checks of docs/validation/cases.md's
/// orientation case.
fn orientation_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let x0 = by_id(sim);
    let mut unit = 0.0f64;
    let wall = match run(sim, |sim| {
        let Column::Quat(q) = &sim.backend().download(&["solid_orientation"])[0] else { panic!("orientations") };
        unit = q.iter().fold(unit, |u, q| u.max((f64::from(q.length()) - 1.0).abs()));
        sim.time() < 1.0
    }) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    let x = by_id(sim);
    let n = x.len() as f32;
    let (c0, c) = (x0.iter().sum::<Vec3>() / n, x.iter().sum::<Vec3>() / n);
    let a = x0.iter().zip(&x).fold(Mat3::ZERO, |a, (&p0, &p)| {
        let (q, r) = (p0 - c0, p - c);
        a + Mat3::from_cols(r * q.x, r * q.y, r * q.z)
    });
    let body = polar::eigen(a);
    let names = [
        "solid_orientation",
        "solid_orientation_before",
        "cluster_rotation",
        "solid_clusters_segment",
        "solid_clusters_member",
        "slot_of",
    ];
    let cols = sim.backend().download(&names);
    let (
        Column::Quat(q),
        Column::Quat(before),
        Column::Quat(rotation),
        Column::U32(segment),
        Column::U32(member),
        Column::U32(slot),
    ) = (&cols[0], &cols[1], &cols[2], &cols[3], &cols[4], &cols[5])
    else {
        panic!("the oriented particles' attributes")
    };
    let orientation_error = q.iter().map(|q| angle_between(*q, body)).fold(0.0, f64::max);
    // Both blends of each particle's clusters' rotations, from the same values.
    let mut qlerp = vec![Quat::from_xyzw(0.0, 0.0, 0.0, 0.0); q.len()];
    let mut logs = vec![(Vec3::ZERO, 0u32); q.len()];
    for (k, &s) in segment.iter().enumerate() {
        let i = slot[member[k] as usize] as usize;
        let (r, b) = (rotation[s as usize], before[i]);
        qlerp[i] += orient::signed(r, b);
        logs[i] = (logs[i].0 + orient::log_turn(r, b), logs[i].1 + 1);
    }
    let blend_difference = (0..q.len())
        .filter(|&i| logs[i].1 > 0)
        .map(|i| angle_between(qlerp[i].normalize(), orient::exp(logs[i].0 / logs[i].1 as f32) * before[i]))
        .fold(0.0, f64::max);
    (
        wall,
        None,
        vec![("unit_length", unit), ("orientation_error", orientation_error), ("blend_difference", blend_difference)],
    )
}

/// The bar's stretch: the RMS distance of its particles from its centre along x.
fn stretch_of(sim: &Simulation) -> f64 {
    let x = by_id(sim);
    let c = x.iter().map(|p| f64::from(p.x)).sum::<f64>() / x.len() as f64;
    (x.iter().map(|p| (f64::from(p.x) - c).powi(2)).sum::<f64>() / x.len() as f64).sqrt()
}

/// Stretches the bar by 10 % along x, releases it for 2 s, and measures its
/// oscillation from the peaks of its stretch over the rest's.
fn stiffness_case(sim: &mut Simulation, _spacing: f64) -> Measured {
    let rest = stretch_of(sim);
    stretch(sim);
    let first = stretch_of(sim) - rest;
    let mut trace: Vec<(f64, f64)> = Vec::new();
    let wall = match run(sim, |sim| {
        trace.push((sim.time(), stretch_of(sim) - rest));
        sim.time() < 2.0
    }) {
        Ok(wall) => wall,
        Err(halted) => return halted,
    };
    // Peaks of the stretch (local maxima above a hundredth of the first).
    let peaks: Vec<(f64, f64)> = trace
        .windows(3)
        .filter(|w| w[1].1 > w[0].1 && w[1].1 >= w[2].1 && w[1].1 > 0.01 * first)
        .map(|w| w[1])
        .collect();
    let (period, decay) = match peaks.as_slice() {
        [a, b, ..] => (b.0 - a.0, b.1 / a.1),
        _ => (0.0, 0.0),
    };
    let left = trace.last().map_or(0.0, |l| l.1.abs() / first);
    (wall, None, vec![("stretch_left", left), ("period", period), ("decay", decay)])
}
