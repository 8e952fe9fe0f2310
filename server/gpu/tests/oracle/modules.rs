//! The modules' passes and whole steps against the CPU: snowfall (with its release),
//! elastic solids, melting, the Stefan problem and heat.

use super::*;

/// Whole steps of snow falling into the dam break's tank, with a slab from an OBJ
/// (a mesh object: columns over the cells) beside the box and the cylinder: the
/// GPU emits the CPU's flakes, lands as many on the ground and on the objects
/// within 1 %, some on the slab, and its accounting adds up exactly.
#[test]
fn snowfall_steps_like_the_cpu() {
    use floe_engine::attrs::Column;
    use floe_engine::modules::snowfall::{Accounts, SnowfallConsts, flakes};
    let Some(gpu) = common::gpu("snowfall_steps_like_the_cpu") else { return };
    let slab = format!(
        "\"objects\":[{{\"shape\":\"mesh\",\"min\":[0.6,0,0],\"max\":[0.9,0.015,0.25],\"mesh\":{{\"data_base64\":\"{SLAB}\"}}}},"
    );
    let snowfall = SNOWFALL.replace("\"objects\":[", &slab);
    let o = ["particle_spacing=0.05", "modules=[\"fluid\",\"snowfall\"]", &snowfall];
    let (mut cpu, mut g) = pair(gpu, "dam_break", &o, 10);
    for _ in 0..60 {
        cpu.step().unwrap();
        g.step().unwrap();
    }
    let (a, b) = (Accounts::of(cpu.backend()), Accounts::of(g.backend()));
    assert_eq!(a.emitted, b.emitted);
    for (name, x, y) in [("ground", a.on_ground, b.on_ground), ("objects", a.on_objects, b.on_objects)] {
        assert!(x > 100 && x.abs_diff(y) as f64 <= 0.01 * x as f64, "landed on the {name}: CPU {x}, GPU {y}");
    }
    for s in [a, b] {
        assert_eq!(s.emitted, s.accounted(), "{s:?}");
    }
    let c = g.model().consts::<SnowfallConsts>().clone();
    let Column::U32(top) = g.backend().download(&["top_count"]).remove(0) else { panic!("counts") };
    assert!(top[flakes::cell(&c, 0.75, 0.125)] > 0, "flakes on the slab");
}

/// A slab 1 x 0.1 x 1 (OBJ, base64).
const SLAB: &str = "diAwIDAgMAp2IDEgMCAwCnYgMSAwIDEKdiAwIDAgMQp2IDAgMC4xIDAKdiAxIDAuMSAwCnYgMSAwLjEgMQp2IDAgMC4xIDEKZiAxIDIgMwpmIDEgMyA0CmYgNSA3IDYKZiA1IDggNwpmIDEgNSA2CmYgMSA2IDIKZiA0IDMgNwpmIDQgNyA4CmYgMSA0IDgKZiAxIDggNQpmIDIgNiA3CmYgMiA3IDMK";

/// The release on the mountain side at 20 cm, restored from the CPU's snapshot
/// before it (4.5 s) on both backends: each releases at 5 s, its particles hold
/// exactly the flakes its cover lost, the two release as many within 2 %, and the
/// avalanche's first steps run on the GPU.
#[test]
fn snowfall_release_steps_like_the_cpu() {
    use floe_engine::modules::snowfall::{Accounts, SnowfallConsts};
    let Some(gpu) = common::gpu("snowfall_release_steps_like_the_cpu") else { return };
    let o = ["particle_spacing=0.2", "snowfall.height=3.2", "snowfall.depth_per_hour=540", "snowfall.release.at=5"];
    let (mut cpu, mut g) = pair(gpu, "snowfall_then_avalanche", &o, 50);
    assert!(cpu.time() < 5.0 && cpu.particle_count() == 0, "restored before the release");
    for sim in [&mut cpu, &mut g] {
        while sim.time() < 5.3 {
            sim.step().unwrap();
        }
    }
    let q = u64::from(cpu.model().consts::<SnowfallConsts>().release.as_ref().unwrap().flakes_per_particle);
    let counts: Vec<u64> = [&cpu, &g]
        .iter()
        .map(|sim| {
            let a = Accounts::of(sim.backend());
            let n = sim.particle_count() as u64;
            assert_eq!(a.emitted, a.accounted(), "{a:?}");
            assert_eq!(a.released, n * q, "{a:?}: {n} particles of {q} flakes");
            n
        })
        .collect();
    assert!(counts[0] > 100 && counts[0].abs_diff(counts[1]) as f64 <= 0.02 * counts[0] as f64, "{counts:?}");
}

/// The jelly of `elastic_drop` (4 cm: 125 particles) after 20 steps, with each
/// rotation method, each cluster solver (the coloured ones reading the sweep),
/// both ways of sharing a Jacobi iteration's ways, a partial damping and
/// oriented particles with each blend:
/// every pass of the shape matching and of the rigid-motion damping against the
/// CPU's, then 20 whole steps on both, whose positions agree within a
/// micrometre, and again after both change to the hybrid solver while running.
#[test]
fn solid_passes_and_steps_match_the_cpu() {
    let Some(gpu) = common::gpu("solid_passes_and_steps_match_the_cpu") else { return };
    for o in [
        &["particle_spacing=0.04"][..],
        &["particle_spacing=0.04", "solid.rotation=\"iterative\"", "solid.solver=\"weighted_jacobi\""],
        &["particle_spacing=0.04", "solid.shares=\"mean\"", "solid.damping=0.5"],
        &["particle_spacing=0.04", "solid.stiffness_applied=\"once_per_step\""],
        &["particle_spacing=0.04", "solid.centre_spacing=1.5"],
        &["particle_spacing=0.04", "solid.solver=\"gauss_seidel\""],
        &["particle_spacing=0.04", "solid.solver=\"hybrid\"", "solid.colours=3"],
        &["particle_spacing=0.04", "solid.oriented={}", "solid.bodies[0].angular_velocity=[0,3,1]"],
        &[
            "particle_spacing=0.04",
            "solid.oriented={\"blend\":\"exp_map\",\"radii\":[1,0.5,0.25]}",
            "solid.bodies[0].angular_velocity=[1,3,0]",
        ],
    ] {
        let (cpu, _) = pair(gpu, "elastic_drop", o, 20);
        let passes: Vec<&'static PassSpec> =
            cpu.model().plan.passes().iter().copied().filter(|p| p.module == "solid").collect();
        let oriented = o.iter().any(|s| s.starts_with("solid.oriented"));
        let once = o.iter().any(|s| s.starts_with("solid.stiffness_applied"));
        assert_eq!(passes.len(), if oriented { 25 } else { 20 } + usize::from(once));
        for pass in passes {
            let (mut c, mut g) = pair(gpu, "elastic_drop", o, 20);
            check_pass(&mut c, &mut g, pass, &format!("{o:?}"));
        }
        let (mut c, mut g) = pair(gpu, "elastic_drop", o, 20);
        for _ in 0..20 {
            c.step().unwrap();
            g.step().unwrap();
        }
        let by_id = |sim: &Simulation| {
            let cols = sim.backend().download(&["x", "id"]);
            let (Column::Vec3(x), Column::U32(id)) = (&cols[0], &cols[1]) else { panic!("positions and ids") };
            let mut out = vec![floe_engine::math::Vec3::ZERO; x.len()];
            x.iter().zip(id).for_each(|(p, &i)| out[i as usize] = *p);
            out
        };
        let worst = by_id(&c).iter().zip(by_id(&g)).map(|(a, b)| a.distance(b)).fold(0.0f32, f32::max);
        assert!(worst < 1e-6, "{o:?}: positions {worst} m apart after 20 steps");
        // Live: both switch solver and iterations and go on stepping alike.
        let live: Vec<String> = ["solid.solver=\"hybrid\"", "solid.iterations=2"].map(String::from).to_vec();
        for sim in [&mut c, &mut g] {
            sim.set_parameters(&live).unwrap();
            for _ in 0..5 {
                sim.step().unwrap();
            }
        }
        let worst = by_id(&c).iter().zip(by_id(&g)).map(|(a, b)| a.distance(b)).fold(0.0f32, f32::max);
        assert!(worst < 1e-6, "{o:?}: positions {worst} m apart after a live change to hybrid");
    }
}

/// The jelly on DFSPH (4 cm), whose shape matching runs before the density solve
/// over the positions the velocities lead to: the core's look-ahead, prediction,
/// velocity update and look-back, and the solid's passes, against the CPU's (its
/// whole steps iterate DFSPH's solves to a tolerance, which the backends may
/// reach an iteration apart; DFSPH's passes have their own oracle test).
#[test]
fn solid_passes_on_dfsph_match_the_cpu() {
    let Some(gpu) = common::gpu("solid_passes_on_dfsph_match_the_cpu") else { return };
    let o = ["particle_spacing=0.04", "solver.method=\"dfsph\""];
    let (cpu, _) = pair(gpu, "elastic_drop", &o, 20);
    let passes: Vec<&'static PassSpec> = cpu
        .model()
        .plan
        .passes()
        .iter()
        .copied()
        .filter(|p| p.module == "solid" || p.name.starts_with("core.look") || p.name == "core.predict")
        .collect();
    for name in ["core.look_ahead", "core.look_back", "core.predict", "solid.damp"] {
        assert!(passes.iter().any(|p| p.name == name), "{name} in the plan");
    }
    for pass in passes {
        let (mut c, mut g) = pair(gpu, "elastic_drop", &o, 20);
        check_pass(&mut c, &mut g, pass, "dfsph");
    }
}

/// The ice cube of `ice_cube_in_glass` (1 cm: 64 particles) at its melting point
/// on water at 350 K, 500 steps in (some of it melting, some melted and gone
/// from its clusters): every pass of heat and of the shape matching against the
/// CPU's, then 20 whole steps on both, whose phases agree exactly and whose
/// positions and liquid fractions agree closely. On WCSPH: the preset's DFSPH
/// iterates its solves to a tolerance, which the backends may reach an iteration
/// apart, and its own passes have their own oracle test. The same with oriented
/// particles.
#[test]
fn melting_passes_and_steps_match_the_cpu() {
    let Some(gpu) = common::gpu("melting_passes_and_steps_match_the_cpu") else { return };
    let o = [
        "solver.method=\"wcsph\"",
        "particle_spacing=0.01",
        "heat.fluids[0].temperature=350",
        "heat.fluids[1].temperature=273.15",
        "fluids[1].blocks[0].min=[0.03,0.08,0.03]",
        "fluids[1].blocks[0].max=[0.07,0.12,0.07]",
    ];
    // Shape matching, and oriented particles (their orientations blended by ExpMap).
    let oriented = [&o[..], &["solid.oriented={\"blend\":\"exp_map\"}"]].concat();
    for o in [&o[..], &oriented[..]] {
        melting_matches(gpu, o);
    }
}

fn melting_matches(gpu: &floe_gpu::GpuContext, o: &[&str]) {
    let (cpu, _) = pair(gpu, "ice_cube_in_glass", o, 500);
    let column = |s: &Simulation, name: &str| s.backend().download(&[name]).remove(0);
    let Column::F32(beta) = column(&cpu, "liquid_fraction") else { panic!("a liquid fraction") };
    assert!(beta.iter().any(|&b| b > 0.0 && b < 1.0) && beta.contains(&1.0), "{o:?}: melting and melted");
    let passes: Vec<&'static PassSpec> =
        cpu.model().plan.passes().iter().copied().filter(|p| p.module != "core").collect();
    for name in ["heat.melt", "solid.leave", "solid.live", "solid.project"] {
        assert!(passes.iter().any(|p| p.name == name), "{name} in the plan");
    }
    // The heat module's passes once, on the first scene.
    let oriented = o.iter().any(|s| s.starts_with("solid.oriented"));
    for pass in passes.into_iter().filter(|p| p.module == "solid" || (p.module == "heat" && !oriented)) {
        let (mut c, mut g) = pair(gpu, "ice_cube_in_glass", o, 500);
        check_pass(&mut c, &mut g, pass, &format!("melting {o:?}"));
    }
    let (mut c, mut g) = pair(gpu, "ice_cube_in_glass", o, 500);
    for _ in 0..20 {
        c.step().unwrap();
        g.step().unwrap();
    }
    let by_id = |sim: &Simulation| {
        let cols = sim.backend().download(&["x", "id", "material", "liquid_fraction"]);
        let (Column::Vec3(x), Column::U32(id), Column::U32(m), Column::F32(b)) =
            (&cols[0], &cols[1], &cols[2], &cols[3])
        else {
            panic!("positions, ids, materials and liquid fractions")
        };
        let mut out = vec![(floe_engine::math::Vec3::ZERO, 0, 0.0); x.len()];
        for k in 0..x.len() {
            out[id[k] as usize] = (x[k], m[k], b[k]);
        }
        out
    };
    let (a, b) = (by_id(&c), by_id(&g));
    assert!(a.iter().zip(&b).all(|(p, q)| p.1 == q.1), "{o:?}: the phases differ after 20 steps");
    let worst = a.iter().zip(&b).map(|(p, q)| p.0.distance(q.0)).fold(0.0f32, f32::max);
    let fraction = a.iter().zip(&b).map(|(p, q)| (p.2 - q.2).abs()).fold(0.0f32, f32::max);
    assert!(
        worst < 1e-5 && fraction < 1e-3,
        "{o:?}: positions {worst} m, liquid fractions {fraction} apart after 20 steps"
    );
}

/// The Stefan slab (2 mm) 200 steps in, melting from its warm wall: heat's passes
/// against the CPU's (conduction writing the walls' part, the enthalpy, the heat
/// taken in), then 100 whole steps whose liquid fractions and heat taken in agree.
#[test]
fn stefan_passes_and_steps_match_the_cpu() {
    let Some(gpu) = common::gpu("stefan_passes_and_steps_match_the_cpu") else { return };
    let (cpu, _) = pair(gpu, "stefan", &[], 200);
    let passes: Vec<&'static PassSpec> =
        cpu.model().plan.passes().iter().copied().filter(|p| p.module == "heat").collect();
    assert_eq!(passes.iter().map(|p| p.name).collect::<Vec<_>>(), ["heat.conduction", "heat.melt", "heat.input"]);
    for pass in passes {
        let (mut c, mut g) = pair(gpu, "stefan", &[], 200);
        check_pass(&mut c, &mut g, pass, "stefan");
    }
    let (mut c, mut g) = pair(gpu, "stefan", &[], 200);
    for _ in 0..100 {
        c.step().unwrap();
        g.step().unwrap();
    }
    for name in ["liquid_fraction", "heat_in", "enthalpy"] {
        let (d, scale) = diff(&c.backend().download(&[name])[0], &g.backend().download(&[name])[0]);
        assert!(scale > 0.0 && d <= 1e-4 * scale, "{name}: {d} apart (largest {scale})");
    }
}

/// Whole steps with heat, dt changing from step to step (the integration reads the
/// stage's dt from the core uniform `dt`): the slab's temperatures after 30 steps agree with
/// the CPU's, and both follow the erf solution.
#[test]
fn heat_steps_like_the_cpu() {
    let Some(gpu) = common::gpu("heat_steps_like_the_cpu") else { return };
    let (mut cpu, mut g) = pair(gpu, "conduction", &["particle_spacing=0.002"], 10);
    let (mut hc, mut hg) = pair(gpu, "convection", &["particle_spacing=0.01", "heat.fluids[0].conductivity=500"], 10);
    for _ in 0..30 {
        for sim in [&mut cpu, &mut g, &mut hc, &mut hg] {
            sim.step().unwrap();
        }
    }
    let temperature = |s: &Simulation| s.backend().download(&["temperature"]).remove(0);
    let (d, scale) = diff(&temperature(&cpu), &temperature(&g));
    assert!(d <= 1e-5 * scale, "conduction: temperatures differ by {d} K");
    assert_eq!(cpu.time(), g.time());
    let (l2, _) = floe_engine::modules::heat::cases::conduction_errors(&g);
    assert!(l2 < 0.01, "GPU conduction: L2 {l2} against the erf solution");
    let mean = |s: &Simulation| s.measures().into_iter().find(|m| m.name == "heat.mean_temperature").unwrap().value;
    assert!((mean(&hc) - mean(&hg)).abs() < 1e-3, "convection: mean {} vs {}", mean(&hc), mean(&hg));
    assert!(mean(&hg) > 310.0 + 1e-4, "the GPU's hot floor did not warm the water: {}", mean(&hg));
}

/// Water heated gently through its floor gains increments under half the f32
/// spacing of its temperature each step; the GPU's compensated integration keeps
/// them as the CPU's does: the heat rises at the flux times the floor's area.
#[test]
fn a_gentle_flux_warms_water_on_the_gpu() {
    let Some(gpu) = common::gpu("a_gentle_flux_warms_water_on_the_gpu") else { return };
    let overrides = [
        "particle_spacing=0.02",
        "gravity=[0,0,0]",
        "solver.speed_of_sound=20",
        "heat.walls=[]",
        r#"heat.fluxes=[{"min":[-1,-1,-1],"max":[1,0,1],"flux":1000}]"#,
    ];
    let (_, mut g) = pair(gpu, "convection", &overrides, 0);
    let heat = |s: &Simulation| s.measures().into_iter().find(|m| m.name == "heat.total_heat").unwrap().value;
    let q0 = heat(&g);
    for _ in 0..1000 {
        g.step().unwrap();
    }
    let (want, rate) = (1000.0 * 0.4 * 0.04, (heat(&g) - q0) / g.time());
    assert!((rate / want - 1.0).abs() < 0.01, "GPU: {rate} W for {want} W");
}
