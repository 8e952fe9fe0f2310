//! Particles born, removed and changing phase, on both backends: ids never reused,
//! the others' order kept, memory flat, streams of the live particles, mass kept
//! across a phase change, a body from a mesh born whole.

use super::*;

/// The dam break with the tracer's births and deaths: `births` born after every
/// step at the first initial positions, particles older than `lifetime` removed.
fn populated(births: u32, lifetime: f32) -> Vec<String> {
    let mut o = traced();
    o.push(format!("tracer={{\"births\":{births},\"lifetime\":{lifetime}}}"));
    o
}

fn ids(b: &dyn Backend) -> Vec<u32> {
    match b.download(&["id"]).remove(0) {
        Column::U32(v) => v,
        other => panic!("ids: {other:?}"),
    }
}

/// Every step replaces all 1,000 particles with 1,000 born (lifetime 0): ids are
/// never reused, the scene holds 1,000 particles and the same memory throughout, a
/// snapshot taken midway steps on bit for bit, and frames carry the live particles.
#[test]
fn particles_are_born_and_die_with_ids_never_reused_and_memory_flat() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        // A million births on the CPU; a tenth of them on a software GPU.
        let steps: u32 = if backend == "cpu" { 1000 } else { 100 };
        let mut sim = Simulation::new(from_preset("dam_break", &populated(1000, 0.0)).unwrap(), &make).unwrap();
        assert_eq!(sim.model().particle_capacity(), 1000 + 10_000);
        let memory = total(sim.backend());
        let mut saved = None;
        for step in 1..=steps {
            sim.step().unwrap();
            if step % 50 == 0 || step == 1 {
                let ids = ids(sim.backend());
                assert_eq!(ids.len(), 1000, "{backend} step {step}");
                // This step's births only: ids from 1000 step on, each once.
                let mut sorted = ids.clone();
                sorted.sort_unstable();
                let first = 1000 * step;
                assert_eq!(sorted, (first..first + 1000).collect::<Vec<_>>(), "{backend} step {step}");
                assert_eq!(total(sim.backend()), memory, "{backend} step {step}: memory changed");
            }
            if step == steps / 2 {
                saved = Some(sim.snapshot());
            }
        }
        assert_eq!(
            sim.model().population.as_ref().unwrap().next_id,
            1000 * (steps + 1),
            "{backend}: {} births",
            1000 * steps
        );
        // The snapshot taken midway steps on bit for bit.
        let mut back = Simulation::restore_on(&saved.unwrap(), &make).unwrap();
        let mut again = Simulation::new(from_preset("dam_break", &populated(1000, 0.0)).unwrap(), &make).unwrap();
        for _ in 0..steps / 2 {
            again.step().unwrap();
        }
        for _ in 0..10 {
            back.step().unwrap();
            again.step().unwrap();
        }
        let state = |s: &Simulation| s.backend().state();
        assert_eq!(state(&back), state(&again), "{backend}: the restored scene steps on as the original");
        // Frames: the live particles, in id order.
        let p = sim.read(&["velocity"]);
        assert_eq!(p.positions.len(), 1000);
    }
}

/// Particles marked for removal go; the others keep their order and state.
#[test]
fn removed_particles_go_and_the_others_keep_their_order() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("dam_break", &populated(0, 1e3)).unwrap(), &make).unwrap();
        for _ in 0..5 {
            sim.step().unwrap();
        }
        let names = ["id", "x", "v", "age"];
        let before = sim.backend().download(&names);
        let Column::U32(id) = &before[0] else { panic!("u32 ids") };
        let keep: Vec<bool> = id.iter().map(|i| i % 3 != 0).collect();
        let remove = Column::F32(keep.iter().map(|&k| if k { 0.0 } else { 1.0 }).collect());
        sim.backend_mut().upload("remove", remove);
        sim.backend_mut().compact();
        let after = sim.backend().download(&names);
        let kept = keep.iter().filter(|&&k| k).count();
        assert_eq!(sim.particle_count(), kept, "{backend}");
        for ((name, b), a) in names.iter().zip(&before).zip(&after) {
            let per = b.elem().components();
            let kept_words: Vec<u32> =
                b.words().chunks(per).zip(&keep).filter(|(_, k)| **k).flat_map(|(w, _)| w.to_vec()).collect();
            assert_eq!(a.words(), kept_words, "{backend}: {name}");
        }
        // The scene steps on with the others.
        sim.step().unwrap();
    }
}

/// Through the service: a scene whose particles are born and die counts its
/// capacity against the limits and streams its live particles, identity-ordered
/// frames naming their ids (each step replaces every particle: ids from 1,000 on, 500
/// a step).
#[tokio::test]
async fn a_scene_whose_particles_are_born_and_die_streams_its_live_particles() {
    floe_engine::module::register(&tracer::MODULE);
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let o = populated(500, 0.0);
    let refs: Vec<&str> = o.iter().map(String::as_str).collect();
    let info = floe.create_preset("dam_break", &refs).await.unwrap();
    assert_eq!(info.particles, 1000 + 5000, "the capacity: 1,000 particles and room for ten steps' births");
    floe.step(info.scene_id, 3).await.unwrap();
    let request = FrameRequest { identity: false, ..FrameRequest::default() };
    let mut frames = floe.frames(info.scene_id, request).await.unwrap();
    let frame = frames.next().await.unwrap().unwrap();
    assert_eq!((frame.header.step, frame.positions.len()), (3, 500));
    let mut identity = floe.frames(info.scene_id, FrameRequest::default()).await.unwrap();
    let frame = identity.next().await.unwrap().unwrap();
    assert_eq!((frame.header.mode, frame.header.step), (floe_proto::Mode::IdentityOrdered, 3));
    let p = identity.particles(frame);
    assert_eq!(p.ids, Some((2000..2500).collect::<Vec<u32>>()), "the third step's births");
    assert_eq!(p.positions.len(), 500);
    floe.step(info.scene_id, 1).await.unwrap();
    let frame = identity.next().await.unwrap().unwrap();
    assert!(frame.header.keyframe, "other particles: a keyframe");
    assert_eq!(identity.particles(frame).ids, Some((2500..3000).collect::<Vec<u32>>()));
    server.shutdown().await;
}

/// The materials of `sim`'s particles.
fn materials(sim: &Simulation) -> Vec<u32> {
    match sim.backend().download(&["material"]).remove(0) {
        Column::U32(m) => m,
        other => panic!("materials: {other:?}"),
    }
}

/// The particles' mean density by summation (kg/m^3).
fn mean_density(sim: &Simulation) -> f64 {
    let p = sim.read(&["density"]);
    let rho = p.channel("density").and_then(Values::as_scalars).unwrap();
    rho.iter().map(|&r| f64::from(r)).sum::<f64>() / rho.len() as f64
}

/// The tracer's phase change: after the first step every particle is older than
/// the phase age and changes into `aged` (rest density 0.9 of water's) keeping its
/// mass; the pressure then pushes the particles apart towards the new rest density
/// (on WCSPH, [`traced_on_wcsph`]: the mean falls to 0.88 of water's in 20 steps),
/// where the same scene without the change stays at water's (0.98); a snapshot
/// holds the materials.
#[test]
fn a_particle_changes_phase_keeping_its_mass_and_the_solver_follows() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    let mut phased = traced_on_wcsph();
    phased.push("tracer={\"phase_age\":0.0}".into());
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("dam_break", &phased).unwrap(), &make).unwrap();
        let mut plain = Simulation::new(from_preset("dam_break", &traced_on_wcsph()).unwrap(), &make).unwrap();
        let table = sim.model().materials.clone();
        let aged = table.iter().position(|m| m.name == tracer::AGED).unwrap() as u32;
        assert_eq!(table.get(aged as usize).mass, table.get(0).mass, "{backend}: a phase keeps the mass");
        assert_eq!(table.get(aged as usize).rest_density, tracer::PHASE_DENSITY * table.get(0).rest_density);
        let n = sim.particle_count();
        assert!(materials(&sim).iter().all(|&m| m == 0), "{backend}: all water at first");
        sim.step().unwrap();
        plain.step().unwrap();
        assert!(materials(&sim).iter().all(|&m| m == aged), "{backend}: all aged after one step");
        assert_eq!(sim.particle_count(), n);
        let saved = sim.snapshot();
        for _ in 0..20 {
            sim.step().unwrap();
            plain.step().unwrap();
        }
        let (rho, rho_plain) = (mean_density(&sim), mean_density(&plain));
        eprintln!("{backend}: mean density {rho:.1} with the phase, {rho_plain:.1} without");
        let rho0 = f64::from(table.get(0).rest_density);
        assert!(rho < 0.95 * rho0 && rho_plain > 0.97 * rho0, "{backend}: {rho} and {rho_plain}");
        // The snapshot holds the materials: restored, it steps on as the original.
        let mut back = Simulation::restore_on(&saved, &make).unwrap();
        assert!(materials(&back).iter().all(|&m| m == aged), "{backend}: restored materials");
        let mut again = Simulation::new(from_preset("dam_break", &phased).unwrap(), &make).unwrap();
        again.step().unwrap();
        for _ in 0..5 {
            back.step().unwrap();
            again.step().unwrap();
        }
        assert_eq!(back.backend().state(), again.backend().state(), "{backend}: restored steps on");
    }
}

/// A closed unit cube, as an OBJ file.
const CUBE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

/// The tracer's body from a mesh asset: read from the assets directory into the
/// scene, born whole after every step inside its box (lifetime 0: every older
/// particle goes); an open mesh is refused naming the field and the file.
#[test]
fn a_body_from_a_mesh_asset_is_born_whole() {
    floe_engine::module::register(&tracer::MODULE);
    floe_gpu::pass::register(&tracer::gpu::MODULE);
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cube.obj"), CUBE_OBJ).unwrap();
    // The cube without its last triangle: open.
    let open = CUBE_OBJ.trim_end().rsplit_once('\n').unwrap().0;
    std::fs::write(dir.path().join("open.obj"), open).unwrap();
    let scene = |asset: &str| {
        let mut o = traced();
        o.push(format!(
            "tracer={{\"lifetime\":0,\"body\":{{\"mesh\":{{\"asset\":\"{asset}\"}},\"min\":[1.4,0.5,0.025],\"max\":[1.6,0.7,0.225]}}}}"
        ));
        let mut scene = from_preset("dam_break", &o).unwrap();
        floe_engine::mesh::read_assets(&mut scene, Some(dir.path())).map(|()| scene)
    };
    let errors = scene("open.obj").unwrap_err();
    assert!(errors.iter().any(|e| e.contains("tracer.body.mesh") && e.contains("open.obj")), "{errors:?}");
    for (backend, make) in factories() {
        let mut sim = Simulation::new(scene("cube.obj").unwrap(), &make).unwrap();
        let body = sim.model().consts::<tracer::TracerConsts>().births.clone();
        // A 0.2 m cube at 0.05 m: 4^3 or 5^3 lattice points, depending on its faces.
        assert!((64..=125).contains(&body.len()), "{backend}: {} particles in the body", body.len());
        for step in 1..=3 {
            sim.step().unwrap();
            assert_eq!(sim.particle_count(), body.len(), "{backend} step {step}");
            assert_eq!(vec3s(sim.backend(), "x"), body, "{backend} step {step}: the body just born");
        }
        let (lo, hi) = (floe_engine::math::Vec3::new(1.4, 0.5, 0.025), floe_engine::math::Vec3::new(1.6, 0.7, 0.225));
        let inside = |p: &floe_engine::math::Vec3| p.cmpge(lo - 1e-6).all() && p.cmple(hi + 1e-6).all();
        assert!(body.iter().all(inside), "{backend}: the body lies in its box");
    }
}
