//! Modules are additive, and absent ones cost nothing:
//! - a module that lives in these tests (`tracer/`), registered with one line, adds
//!   attributes, passes, channels and a second particle set, and its channels
//!   stream to a client as any other;
//! - a solid's particles are a set of their own, and melting moves them to the
//!   fluid's (`modules/parts.rs`);
//! - for every preset on both backends, nothing is allocated or run for a module
//!   the scene does not use, and the memory a module's attribute adds is exactly
//!   what the attribute declares.

mod common;
// Births, deaths, phase changes: a folder beside this file (tests/ builds every file
// at its top as a test of its own).
#[path = "modules/parts.rs"]
mod parts;
#[path = "modules/population.rs"]
mod population;
mod tracer;

use floe_client::{Client, FrameRequest};
use floe_engine::Simulation;
use floe_engine::attrs::Column;
use floe_engine::backend::Backend;
use floe_engine::model::Model;
use floe_engine::scene::load::from_preset;
use floe_engine::simulation::BackendFactory;
use floe_proto::Values;

/// The dam break at a coarse spacing, with the tracer module listed.
fn traced() -> Vec<String> {
    vec!["particle_spacing=0.05".into(), "modules=[\"fluid\",\"tracer\"]".into()]
}

/// [`traced`] on WCSPH, whose position solves run after the drift: the tracer's
/// floor holds at the end of every step (on DFSPH the density solve that follows
/// the floor pushes particles through it, `tracer/mod.rs`).
fn traced_on_wcsph() -> Vec<String> {
    let mut o = traced();
    o.push("solver.method=\"wcsph\"".into());
    o
}

#[tokio::test]
async fn a_module_of_the_tests_adds_attributes_passes_a_set_and_streams_its_channels() {
    floe_engine::module::register(&tracer::MODULE);
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let o: Vec<String> = traced();
    let refs: Vec<&str> = o.iter().map(String::as_str).collect();
    let info = floe.create_preset("dam_break", &refs).await.unwrap();
    // The scene lists the module's channels, under per-scene tags, and its set.
    let age = info.channels.iter().find(|c| c.name == "age").expect("the age channel");
    assert_eq!((age.unit.as_str(), age.components, age.module.as_str()), ("s", 1, "tracer"));
    assert!(age.tag >= 64, "a channel without a row in channels.json gets a per-scene tag");
    let sets: Vec<(&str, u64, u32)> = info.sets.iter().map(|s| (s.name.as_str(), s.count, s.index)).collect();
    assert_eq!(sets, [("particles", 1000, 0), ("probes", 4, 1), ("columns", 64, 2)]);
    let stepped = floe.step(info.scene_id, 25).await.unwrap();
    let t = stepped.sim_time as f32;

    // Every particle's age is the simulated time (f32 sums of dt).
    let request = FrameRequest { channels: vec!["age".into()], ..FrameRequest::default() };
    let mut frames = floe.frames(info.scene_id, request).await.unwrap();
    let frame = frames.next().await.unwrap().unwrap();
    let particles = frames.particles(frame);
    let ages = particles.channel("age").and_then(Values::as_scalars).unwrap();
    assert_eq!(ages.len(), 1000);
    assert!(ages.iter().all(|a| (a - t).abs() <= 1e-4 * t), "ages {:?} at t = {t}", &ages[..3]);

    // The probes stream as a set of their own.
    let request = FrameRequest { channels: vec!["probe_age".into()], set: "probes".into(), ..FrameRequest::default() };
    let mut probes = floe.frames(info.scene_id, request).await.unwrap();
    let frame = probes.next().await.unwrap().unwrap();
    assert_eq!(frame.header.set, 1);
    let p = probes.particles(frame);
    assert_eq!((p.set.as_str(), p.positions.len()), ("probes", 4));
    assert!((p.positions[3][0] - 0.3).abs() < 1e-4);
    let mean = p.channel("probe_age").and_then(Values::as_scalars).unwrap();
    assert!(mean.iter().all(|a| (a - t).abs() <= 1e-4 * t), "probe ages {mean:?} at t = {t}");

    // The columns stream as grid frames: cells, no positions; a grid is sent whole.
    let columns = info.sets.iter().find(|s| s.name == "columns").expect("the columns set");
    assert!(columns.grid && columns.count == 64);
    let request =
        FrameRequest { channels: vec!["column_count".into()], set: "columns".into(), ..FrameRequest::default() };
    let mut grid = floe.frames(info.scene_id, request).await.unwrap();
    let frame = grid.next().await.unwrap().unwrap();
    assert_eq!(frame.header.mode, floe_proto::Mode::Grid);
    let max_error = frame.header.channels.iter().map(|c| c.ranges[0].max_error).fold(0.0, f32::max);
    let cells = grid.particles(frame);
    let g = cells.grid.expect("a grid frame's cells");
    assert_eq!((g.dims, cells.positions.len()), ([8, 1, 8], 0));
    let counts = cells.channel("column_count").and_then(Values::as_scalars).unwrap();
    let total: f32 = counts.iter().sum();
    assert!((total - 1000.0).abs() <= 64.0 * max_error, "{total} particles over the cells (error {max_error})");
    let request = FrameRequest { set: "columns".into(), decimation: 2, ..FrameRequest::default() };
    let e = floe.frames(info.scene_id, request).await.unwrap_err();
    assert_eq!(common::code(&e), tonic::Code::InvalidArgument, "{e}");
    assert!(e.to_string().contains("decimation: set columns is a grid, sent whole"), "{e}");
    server.shutdown().await;
}

/// A quaternion and a 3x3 matrix per particle: stepped, read as a channel, and
/// carried through a snapshot bit for bit.
#[test]
fn rotations_and_matrices_are_attributes_like_any_other() {
    floe_engine::module::register(&tracer::MODULE);
    let mut sim = Simulation::new_cpu(from_preset("dam_break", &traced()).unwrap()).unwrap();
    for _ in 0..20 {
        sim.step().unwrap();
    }
    let t = sim.time() as f32;
    let p = sim.read(&["spin"]);
    let spin = p.channel("spin").unwrap();
    let Values::Float { components: 4, data } = spin else { panic!("four components: {spin:?}") };
    let q = floe_engine::math::Quat::from_slice(&data[..4]);
    let (axis, angle) = q.to_axis_angle();
    assert!((angle - t).abs() < 1e-4 && (axis.y - 1.0).abs() < 1e-4, "{axis} {angle} at t = {t}");
    let state = sim.backend().state();
    let frame = state.iter().find(|s| s.name == "frame");
    assert!(frame.is_none(), "a derived matrix is not saved");
    let saved = sim.snapshot();
    let mut back = Simulation::restore(&saved).unwrap();
    for _ in 0..5 {
        sim.step().unwrap();
        back.step().unwrap();
    }
    let words = |s: &Simulation, name: &str| {
        let state = s.backend().state();
        state.iter().find(|c| c.name == name).map(|c| c.column.words()).unwrap()
    };
    assert_eq!(words(&sim, "spin"), words(&back, "spin"));
    let frames: Vec<_> = sim.backend().allocations().into_iter().filter(|a| a.name == "frame").collect();
    assert_eq!(frames[0].bytes, 36 * sim.particle_count() as u64, "nine f32 per particle on the CPU");
}

/// A module with a pass the GPU lacks.
static CPU_ONLY: floe_engine::module::ModuleDef = floe_engine::module::ModuleDef {
    id: "cpu_only",
    about: "A pass with no GPU half (a module of the tests).",
    requires: &["fluid"],
    section: None,
    validate: |_, _| {},
    count: |_| Vec::new(),
    materials: |_| 0,
    claims: |_| Vec::new(),
    particles: |_, _| Ok(()),
    build: |_, b| {
        b.pass(&NOTHING);
        Ok(())
    },
    retune: |_, _| {},
    tunables: &[],
    cpu: &[("cpu_only.nothing", &Nothing)],
    presets: &[],
    dt_limit: |_| None,
    measures: |_| Vec::new(),
    cases: &[],
    stability: &[],
    bench: &[],
};

static NOTHING: floe_engine::plan::PassSpec = floe_engine::plan::PassSpec {
    name: "cpu_only.nothing",
    module: "cpu_only",
    stage: floe_engine::plan::Stage::PostStep,
    reads: &[],
    writes: &[],
    accumulates: &[],
    tolerance: 0.0,
};

#[derive(Debug)]
struct Nothing;

impl floe_engine::cpu::CpuPass for Nothing {
    fn run(&self, _: &mut floe_engine::cpu::CpuCx<'_>) {}
}

#[test]
fn a_gpu_refuses_a_module_pass_it_lacks_by_name() {
    floe_engine::module::register(&CPU_ONLY);
    let Some(gpu) = gpu() else { return };
    let o = ["particle_spacing=0.05".to_string(), "modules=[\"fluid\",\"cpu_only\"]".to_string()];
    let model = Model::build(&from_preset("dam_break", &o).unwrap()).unwrap();
    let e = floe_gpu::GpuBackend::new(gpu, model).unwrap_err().to_string();
    assert_eq!(
        e,
        "backend: pass cpu_only.nothing (module cpu_only) has no GPU implementation; run this scene on the CPU backend"
    );
}

/// A GPU for these tests, or `None` (saying why) where there is none.
fn gpu() -> Option<&'static floe_gpu::GpuContext> {
    static GPU: std::sync::OnceLock<Result<floe_gpu::GpuContext, String>> = std::sync::OnceLock::new();
    match GPU.get_or_init(|| floe_gpu::GpuContext::new(floe_gpu::Adapters::Any, false).map_err(|e| e.to_string())) {
        Ok(g) => Some(g),
        Err(e) if std::env::var_os("FLOE_REQUIRE_GPU").is_some() => panic!("FLOE_REQUIRE_GPU is set: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: no GPU ({e})");
            None
        }
    }
}

/// The backends to check: the CPU's, and the GPU's where there is one.
fn factories() -> Vec<(&'static str, Box<BackendFactory>)> {
    let mut out: Vec<(&'static str, Box<BackendFactory>)> =
        vec![("cpu", Box::new(floe_engine::simulation::cpu_backend))];
    if let Some(gpu) = gpu() {
        let make = move |model| floe_gpu::GpuBackend::new(gpu, model).map(|b| Box::new(b) as Box<dyn Backend>);
        out.push(("gpu", Box::new(make)));
    }
    out
}

#[test]
fn an_absent_module_allocates_and_runs_nothing() {
    floe_engine::module::register(&tracer::MODULE);
    for (backend, make) in factories() {
        for preset in floe_engine::scene::presets::names() {
            // Presets too small for a 0.05 m spacing run at their own.
            let build = |o: &[String]| {
                let scene = from_preset(preset, o).map_err(|e| e.to_string())?;
                Simulation::new(scene, &make).map_err(|e| e.to_string())
            };
            let mut sim = build(&["particle_spacing=0.05".into()]).or_else(|_| build(&[])).unwrap();
            for _ in 0..3 {
                sim.step().unwrap();
            }
            let scene = sim.scene().modules.clone();
            // The core's shared viscosity is there where a module of the scene claims it.
            let viscous = sim.model().quantities.integration().is_some();
            let present = |m: &str| {
                m == "core"
                    || m == sim.model().scheme.id
                    || scene.iter().any(|s| s == m)
                    || (m == floe_engine::viscosity::MODULE && viscous)
            };
            for a in sim.backend().allocations() {
                assert!(present(a.module), "{backend} {preset}: {} allocated for absent module {}", a.name, a.module);
            }
            for pass in sim.backend().passes_run() {
                let module = pass.split('.').next().unwrap();
                assert!(present(module), "{backend} {preset}: pass {pass} of an absent module ran");
            }
            assert!(!sim.backend().passes_run().is_empty());
        }
    }
}

/// Bytes a backend holds for a scene, in all.
fn total(b: &dyn Backend) -> u64 {
    b.allocations().iter().map(|a| a.bytes).sum()
}

#[test]
fn what_a_module_adds_is_what_its_attributes_declare() {
    floe_engine::module::register(&tracer::MODULE);
    // The tracer module (CPU).
    let without = Simulation::new_cpu(from_preset("dam_break", &["particle_spacing=0.05".into()]).unwrap()).unwrap();
    let with = Simulation::new_cpu(from_preset("dam_break", &traced()).unwrap()).unwrap();
    let added: Vec<_> = with.backend().allocations().into_iter().filter(|a| a.module == "tracer").collect();
    let declared: u64 = with
        .model()
        .layout
        .specs()
        .filter(|s| s.module == "tracer")
        .map(|s| s.elem.cpu_bytes() as u64 * with.model().layout.count(s.space) as u64)
        .sum();
    assert_eq!(added.iter().map(|a| a.bytes).sum::<u64>(), declared);
    // Per particle: age, spin, frame, its memberships' first and count, its groups'
    // sum, its depth below the floor; per membership (two a particle): member,
    // segment, live, order, and two vectors; per group: start, len, a vector; four
    // probes; 64 columns' counts.
    assert_eq!(
        declared,
        (4 + 16 + 36 + 8 + 12 + 4) * 1000 + (16 + 24) * 2000 + (8 + 12) * 16 + 12 * 4 + 4 * 4 + 4 * 64
    );
    // The core adds the positions a position solve starts from and, on DFSPH whose
    // position solves run ahead of the density solve, the positions they look ahead from.
    assert_eq!(total(with.backend()) - total(without.backend()), declared + (12 + 12) * 1000);
    // XSPH, on both backends: its corrections are the fluid's optional attribute.
    for (backend, make) in factories() {
        let scene =
            |xsph: &str| from_preset("dam_break", &["particle_spacing=0.05".into(), format!("fluids[0].xsph={xsph}")]);
        let off = Simulation::new(scene("0").unwrap(), &make).unwrap();
        let on = Simulation::new(scene("0.1").unwrap(), &make).unwrap();
        let n = on.particle_count() as u64;
        let per = if backend == "gpu" { 16 } else { 12 };
        assert_eq!(total(on.backend()) - total(off.backend()), per * n, "{backend}: XSPH adds its vectors only");
    }
}

#[test]
fn a_module_bound_halts_the_scene_naming_the_particle() {
    floe_engine::module::register(&tracer::MODULE);
    for (bad, says) in [(f32::NAN, "non-finite age (NaN)"), (5e3, "is outside its range [0, 1000] s")] {
        let mut sim = Simulation::new_cpu(from_preset("dam_break", &traced()).unwrap()).unwrap();
        sim.step().unwrap();
        let mut age = sim.backend().download(&["age"]).remove(0);
        let Column::F32(values) = &mut age else { panic!("age is f32") };
        values[17] = bad;
        sim.backend_mut().upload("age", age);
        let id = sim.backend_mut().particle_id(17);
        let halted = sim.step().unwrap_err();
        assert_eq!(halted.particle, Some(id), "{halted}");
        assert!(halted.reason.contains(says), "{halted}");
    }
}

/// Every membership's member, segment and live flag, the positions and ids, and
/// the tracer's sums, from `b`.
fn group_sums(b: &dyn Backend) -> (Vec<floe_engine::math::Vec3>, Vec<floe_engine::math::Vec3>) {
    let names = ["x", "id", "tracer_groups_member", "tracer_groups_segment", "tracer_groups_live"];
    let c = b.download(&names);
    let (Column::Vec3(x), Column::U32(id), Column::U32(member), Column::U32(segment), Column::U32(live)) =
        (&c[0], &c[1], &c[2], &c[3], &c[4])
    else {
        panic!("types")
    };
    let mut slot = vec![0; id.len()];
    for (k, &i) in id.iter().enumerate() {
        slot[i as usize] = k;
    }
    let live = |k: usize| live[k] != 0;
    let mut groups = vec![floe_engine::math::Vec3::ZERO; tracer::GROUP_COUNT];
    for k in (0..member.len()).filter(|&k| live(k)) {
        groups[segment[k] as usize] += x[slot[member[k] as usize]];
    }
    let mut particles = vec![floe_engine::math::Vec3::ZERO; x.len()];
    for k in (0..member.len()).filter(|&k| live(k)) {
        particles[slot[member[k] as usize]] += groups[segment[k] as usize];
    }
    (groups, particles)
}

fn vec3s(b: &dyn Backend, name: &str) -> Vec<floe_engine::math::Vec3> {
    match b.download(&[name]).remove(0) {
        Column::Vec3(v) => v,
        other => panic!("{name}: {other:?}"),
    }
}

/// The tracer's groups on a backend: each group's sum is its live members'
/// positions summed in membership order, each particle's the sum of its groups';
/// a member that leaves both its groups drops out of the sums, and the snapshot
/// keeps it out.
fn groups_follow_the_map(make: &BackendFactory, backend: &str) {
    let mut sim = Simulation::new(from_preset("dam_break", &traced()).unwrap(), make).unwrap();
    for _ in 0..3 {
        sim.step().unwrap();
    }
    let (groups, particles) = group_sums(sim.backend());
    assert_eq!(vec3s(sim.backend(), "group_x_sum"), groups, "{backend}");
    assert_eq!(vec3s(sim.backend(), "group_sums"), particles, "{backend}");
    // Particle 5 leaves both its groups.
    let c = sim.backend().download(&["tracer_groups_member", "tracer_groups_live"]);
    let (Column::U32(member), Column::U32(mut live)) = (c[0].clone(), c[1].clone()) else { panic!("u32") };
    for (k, _) in member.iter().enumerate().filter(|(_, m)| **m == 5) {
        live[k] = 0;
    }
    assert_eq!(live.iter().filter(|&&l| l == 0).count(), 2);
    sim.backend_mut().upload("tracer_groups_live", Column::U32(live.clone()));
    sim.step().unwrap();
    let (groups, particles) = group_sums(sim.backend());
    assert_eq!(vec3s(sim.backend(), "group_x_sum"), groups, "{backend}: without particle 5");
    assert_eq!(vec3s(sim.backend(), "group_sums"), particles, "{backend}: without particle 5");
    let slot5 = (0..sim.particle_count() as u32).find(|&k| sim.backend_mut().particle_id(k) == 5).unwrap();
    assert_eq!(particles[slot5 as usize], floe_engine::math::Vec3::ZERO, "{backend}: particle 5 is in no group");
    let back = Simulation::restore_on(&sim.snapshot(), make).unwrap();
    assert_eq!(back.backend().download(&["tracer_groups_live"]).remove(0), Column::U32(live), "{backend}");
}

#[test]
fn a_map_sums_its_segments_and_members_and_a_member_can_leave() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        groups_follow_the_map(&make, backend);
    }
}

/// The floor solve: every step converges in at most one iteration (of four
/// sweeps, one colour each: with a sweep index that did not reach the passes, a
/// quarter of the particles would be lifted per iteration and the solve would
/// never converge), leaves no particle below the floor, and its velocity update
/// is the displacement over dt. On WCSPH, whose solves run after the drift.
#[test]
fn a_position_solve_sweeps_colours_and_updates_velocities() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("dam_break", &traced_on_wcsph()).unwrap(), &make).unwrap();
        let floor = sim.model().consts::<tracer::TracerConsts>().floor;
        let mut lifted = 0;
        for step in 0..40 {
            let report = sim.step().unwrap();
            let solve = report.solves.iter().find(|s| s.name == "tracer.floor").expect("the floor solve reports");
            assert!(solve.iterations <= 1 && solve.residual == 0.0, "{backend} step {step}: {solve:?}");
            lifted += solve.iterations;
            let lowest = vec3s(sim.backend(), "x").iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
            assert!(lowest >= floor, "{backend} step {step}: a particle at {lowest} m below the floor {floor} m");
        }
        assert!(lifted > 5, "{backend}: the floor lifted particles in {lifted} of 40 steps");
        // The core's halves by hand: keep the prediction, move every position, and
        // the velocity gains the displacement over dt.
        let (v0, dt) = (vec3s(sim.backend(), "v"), 2e-3);
        let b = sim.backend_mut();
        b.run_pass("core.predict", dt);
        b.end_step();
        let predicted = vec3s(b, "x");
        let lifted: Vec<_> =
            predicted.iter().enumerate().map(|(i, p)| *p + floe_engine::math::Vec3::Y * (1e-5 * i as f32)).collect();
        b.upload("x", Column::Vec3(lifted.clone()));
        b.run_pass("core.velocity_from_positions", dt);
        b.end_step();
        assert_eq!(vec3s(b, "x_predicted"), predicted, "{backend}");
        let v = vec3s(b, "v");
        for i in 0..v.len() {
            let expected = v0[i] + (lifted[i] - predicted[i]) * (1.0 / dt);
            assert!(
                (v[i] - expected).abs().max_element() <= 1e-6 * expected.abs().max_element().max(1.0),
                "{backend} {i}"
            );
        }
    }
}

/// The tracer's own kernels, registered from outside floe-gpu, step as its CPU
/// passes do: every age is the simulated time, every spin turned by it, every
/// probe the mean age.
#[test]
fn a_module_of_the_tests_runs_on_every_backend() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("dam_break", &traced()).unwrap(), &make).unwrap();
        for _ in 0..20 {
            sim.step().unwrap();
        }
        let t = sim.time() as f32;
        let p = sim.read(&["age", "spin"]);
        let ages = p.channel("age").and_then(Values::as_scalars).unwrap();
        assert!(ages.iter().all(|a| (a - t).abs() <= 1e-4 * t), "{backend}: ages {:?} at t = {t}", &ages[..3]);
        let Some(Values::Float { components: 4, data }) = p.channel("spin") else { panic!("{backend}: spin") };
        let (axis, angle) = floe_engine::math::Quat::from_slice(&data[..4]).to_axis_angle();
        assert!((angle - t).abs() < 1e-4 && (axis.y - 1.0).abs() < 1e-4, "{backend}: {axis} {angle} at t = {t}");
        let Column::F32(probes) = sim.backend().download(&["probe_age"]).remove(0) else { panic!("f32") };
        assert!(probes.iter().all(|a| (a - t).abs() <= 1e-4 * t), "{backend}: probes {probes:?} at t = {t}");
    }
}

/// Counts of the particles above each cell of the tracer's columns, from `b`'s positions.
fn columns_from_positions(b: &dyn Backend, grid: &floe_proto::GridInfo) -> Vec<f32> {
    let mut counts = vec![0.0; (grid.dims[0] * grid.dims[2]) as usize];
    for p in vec3s(b, "x") {
        if let Some(k) = tracer::column_of(grid, p) {
            counts[k] += 1.0;
        }
    }
    counts
}

/// A module's grid reads as a set of cells, no positions, values x fastest, and
/// changes as the scene runs.
#[test]
fn a_grid_is_a_set_of_cells_that_changes() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("dam_break", &traced()).unwrap(), &make).unwrap();
        let (spec, cells) = sim.sets().into_iter().find(|(s, _)| s.name == "columns").expect("the columns set");
        let grid = spec.grid.expect("a grid");
        assert_eq!((grid.dims, cells), ([8, 1, 8], 64));
        let mut seen = Vec::new();
        for _ in 0..3 {
            for _ in 0..15 {
                sim.step().unwrap();
            }
            let p = sim.read_set(&spec, &["column_count"]);
            assert!(p.positions.is_empty() && p.grid == Some(grid), "{backend}");
            let counts = p.channel("column_count").and_then(Values::as_scalars).unwrap().to_vec();
            assert_eq!(counts, columns_from_positions(sim.backend(), &grid), "{backend}");
            assert_eq!(
                counts.iter().sum::<f32>(),
                sim.particle_count() as f32,
                "{backend}: every particle is above a cell"
            );
            seen.push(counts);
        }
        assert!(seen[0] != seen[2], "{backend}: the columns change as the water flows");
    }
}

/// A ground that grows is ground particles land on: the tracer raises the core's
/// `ground_height` under the avalanche preset's snow, and every particle over the
/// terrain stays on or above the ground as it is now, not as it was rasterised; the
/// raised ground is saved with the scene.
#[test]
fn a_ground_that_grows_is_ground_particles_land_on() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    let o = ["particle_spacing=0.1".to_string(), r#"modules=["fluid","snow","tracer"]"#.to_string()];
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("avalanche", &o).unwrap(), &make).unwrap();
        let Column::F32(raster) = sim.backend().download(&["ground_height"]).remove(0) else { panic!("f32") };
        while sim.time() < 0.25 {
            sim.step().unwrap();
        }
        let risen = tracer::RISE * sim.time() as f32;
        assert!(risen >= 0.05, "{backend}: the ground rose {risen} m");
        let Column::F32(ground) = sim.backend().download(&["ground_height"]).remove(0) else { panic!("f32") };
        for (g, r) in ground.iter().zip(&raster) {
            assert!((g - r - risen).abs() <= 1e-4, "{backend}: ground {g} m over the raster's {r} m, not {risen} m");
        }
        let terrain = sim.model().wall_constraints.iter().find_map(|w| match w {
            floe_engine::boundary::WallConstraint::Terrain(t) => Some(t.clone()),
            _ => None,
        });
        let t = terrain.expect("the avalanche has a terrain");
        let mut over = 0;
        for p in vec3s(sim.backend(), "x").into_iter().filter(|p| t.grid.covers(p.x, p.z)) {
            let (h, _) = t.grid.eval_on(&ground[t.first..], p.x, p.z);
            assert!(p.y >= h - 1e-4, "{backend}: a particle at {p} under the ground at {h} m");
            over += 1;
        }
        assert!(over > 100, "{backend}: {over} particles over the terrain");
        let back = Simulation::restore_on(&sim.snapshot(), &make).unwrap();
        assert_eq!(back.backend().download(&["ground_height"]).remove(0), Column::F32(ground), "{backend}");
    }
}
