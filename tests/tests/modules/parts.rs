//! A solid's particles as a set of their own: `solid` and `fluid`, the parts of the
//! SPH particles by their material's kind, on both backends and in frames; melting
//! moves particles from one to the other with their ids.

use super::*;

/// The ice bunny at 2 cm, just below its melting point and with a latent heat of
/// 1 kJ/kg (nature's is 334), dropped into water at 360 K: it melts within tenths
/// of a second of landing.
fn melting() -> Vec<String> {
    [
        "particle_spacing=0.02",
        "heat.fluids[1].temperature=273.1",
        "heat.fluids[1].melting.latent_heat=1000",
        "heat.fluids[0].temperature=360",
    ]
    .map(String::from)
    .to_vec()
}

/// The ids of set `name` of `sim`, in identity order, checked ascending.
fn set_ids(sim: &Simulation, name: &str) -> Vec<u32> {
    let (set, _) = sim.sets().into_iter().find(|(s, _)| s.name == name).unwrap_or_else(|| panic!("no set {name}"));
    let p = sim.read_set(&set, &["velocity"]);
    let ids: Vec<u32> = (0..p.positions.len()).map(|i| p.id(i)).collect();
    assert!(ids.windows(2).all(|w| w[0] < w[1]), "{name}: ids not ascending");
    assert_eq!(p.channel("velocity").map(Values::len), Some(ids.len()), "{name}: the particles' channels");
    ids
}

/// `solid` and `fluid` split the SPH particles: disjoint, together all of them.
fn split(sim: &Simulation) -> (usize, usize) {
    let (all, solid, fluid) = (set_ids(sim, "particles"), set_ids(sim, "solid"), set_ids(sim, "fluid"));
    let mut both = [solid.clone(), fluid.clone()].concat();
    both.sort_unstable();
    assert_eq!(both, all, "at {} s the parts are not the particles", sim.time());
    (solid.len(), fluid.len())
}

/// On both backends: the ice bunny's particles stream as the `solid` set, the water
/// as `fluid`; as the bunny melts the solid set shrinks and the fluid grows by as
/// many, every particle keeping its id.
#[test]
fn melting_moves_particles_from_the_solid_set_to_the_fluid_set_keeping_ids() {
    for (backend, make) in factories() {
        let mut sim = Simulation::new(from_preset("ice_melting", &melting()).unwrap(), &make).unwrap();
        let names: Vec<&str> = sim.model().sets.iter().map(|s| s.name).collect();
        assert_eq!(names, ["particles", "solid", "fluid"], "{backend}");
        let (ice, water) = split(&sim);
        assert!(ice > 500 && water > 500, "{backend}: {ice} ice, {water} water at the start");
        let mut last = (ice, water);
        while sim.time() < 0.6 && last.0 >= ice * 9 / 10 {
            for _ in 0..10 {
                sim.step().unwrap_or_else(|h| panic!("{backend}: {h:?}"));
            }
            let now = split(&sim);
            assert!(now.0 <= last.0, "{backend}: the solid set grew from {} to {} at {} s", last.0, now.0, sim.time());
            last = now;
        }
        assert!(last.0 < ice * 9 / 10, "{backend}: {} of {ice} ice particles left at {} s", last.0, sim.time());
        assert_eq!(last.0 + last.1, ice + water, "{backend}");
    }
}

/// Scenes of solids alone have a solid set of all their particles and no fluid set.
#[test]
fn a_scene_of_solids_alone_has_a_solid_set_of_every_particle() {
    for preset in ["elastic_drop", "bunny"] {
        let o = vec!["particle_spacing=0.02".to_string()];
        let sim = Simulation::new_cpu(from_preset(preset, &o).unwrap()).unwrap();
        let names: Vec<&str> = sim.model().sets.iter().map(|s| s.name).collect();
        assert_eq!(names, ["particles", "solid"], "{preset}");
        assert_eq!(set_ids(&sim, "solid"), set_ids(&sim, "particles"), "{preset}");
    }
    // A fluid alone has no parts.
    let sim = Simulation::new_cpu(from_preset("dam_break", &traced()[..1]).unwrap()).unwrap();
    assert_eq!(sim.model().sets.iter().map(|s| s.name).collect::<Vec<_>>(), ["particles"]);
}

/// Over gRPC: the scene lists the parts, their frames (identity-ordered) carry ids
/// and the particles' channels, and the solid and fluid frames of one step split
/// the particles' frame of it.
#[tokio::test]
async fn frames_of_the_solid_and_fluid_sets_split_the_particles() {
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let o = melting();
    let refs: Vec<&str> = o.iter().map(String::as_str).collect();
    let info = floe.create_preset("ice_melting", &refs).await.unwrap();
    let sets: Vec<(&str, &str)> = info.sets.iter().map(|s| (s.name.as_str(), s.part_of.as_str())).collect();
    assert_eq!(sets, [("particles", ""), ("solid", "particles"), ("fluid", "particles")]);
    let all = info.sets[0].count;
    assert_eq!(info.sets[1].count + info.sets[2].count, all);
    let mut solid = Vec::new();
    for steps in [1, 60] {
        floe.step(info.scene_id, steps).await.unwrap();
        let mut frames = Vec::new();
        for set in ["particles", "solid", "fluid"] {
            let request =
                FrameRequest { set: set.into(), channels: vec!["temperature".into()], ..FrameRequest::default() };
            let mut stream = floe.frames(info.scene_id, request).await.unwrap();
            let frame = stream.next().await.unwrap().unwrap();
            let p = stream.particles(frame);
            assert_eq!(p.set, set);
            assert_eq!(p.channel("temperature").map(Values::len), Some(p.positions.len()), "{set}");
            frames.push(p);
        }
        let ids = |p: &floe_proto::Particles| (0..p.positions.len()).map(|i| p.id(i)).collect::<Vec<u32>>();
        let mut both = [ids(&frames[1]), ids(&frames[2])].concat();
        both.sort_unstable();
        assert_eq!(both, ids(&frames[0]), "after {steps} steps");
        assert_eq!(frames[0].positions.len() as u64, all);
        // A particle's position is the same in its part's frame as in the particles'.
        let at = |p: &floe_proto::Particles, id: u32| p.positions[ids(p).binary_search(&id).unwrap()];
        let first = ids(&frames[1])[0];
        let (a, b) = (at(&frames[1], first), at(&frames[0], first));
        assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-3), "particle {first}: {a:?} and {b:?}");
        solid.push(frames[1].positions.len());
    }
    assert!(solid[1] < solid[0], "the solid set did not shrink: {solid:?}");
}
