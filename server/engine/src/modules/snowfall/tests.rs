use super::*;
use crate::scene::load::from_preset;

fn errors(overrides: &[&str]) -> String {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match from_preset("snow_roof", &o) {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_settings_are_named_by_path() {
    assert!(errors(&["snowfall.area.max=[0,4]"]).contains("snowfall.area.max[0]: must exceed area.min[0] = 0, got 0"));
    assert!(errors(&["snowfall.height=-1"]).contains("snowfall.height: must lie above the floor (0 m), got -1"));
    assert!(errors(&["snowfall.terminal_speed=0"]).contains("snowfall.terminal_speed"));
    assert!(errors(&["snowfall.wind=[1,NaN]"]).contains("snowfall.wind"), "{}", errors(&["snowfall.wind=[1,NaN]"]));
    assert!(errors(&["snowfall.gusts=2"]).contains("snowfall.gusts"));
    let cylinder = r#"snowfall.objects=[{"shape":"cylinder","centre":[1,1],"radius":-1,"bottom":1,"top":0}]"#;
    let e = errors(&[cylinder]);
    assert!(e.contains("snowfall.objects[0].radius") && e.contains("snowfall.objects[0].top"), "{e}");
    let many = format!("snowfall.objects=[{}]", vec![r#"{"shape":"box","min":[0,0,0],"max":[1,1,1]}"#; 17].join(","));
    assert!(errors(&[&many]).contains("at most 16 objects, got 17"));
    assert!(errors(&["snowfall.cell=0.001"]).contains("snowfall.cell: the snow grid would have 16000 x 4000 cells"));
    assert!(errors(&["snowfall.intensity=\"drizzle\""]).contains("snowfall.intensity"));
    let junk =
        r#"snowfall.objects=[{"shape":"mesh","min":[1,0,1],"max":[2,1,2],"mesh":{"data_base64":"bm90IGEgbWVzaA=="}}]"#;
    assert!(errors(&[junk]).contains("snowfall.objects[0].mesh"), "{}", errors(&[junk]));
}

/// The valley under snow for 20 s on the CPU: every flake emitted is in the air,
/// on the ground, on an object or gone, exactly, at every step; snow lies on the
/// ground and on the objects; the ring never overwrites a flake in the air (it
/// would vanish from the accounts).
#[test]
fn every_flake_is_accounted_for() {
    let mut sim = crate::Simulation::new_cpu(from_preset("snowfall", &[]).unwrap()).unwrap();
    while sim.time() < 20.0 {
        sim.step().unwrap();
        let a = Accounts::of(sim.backend());
        assert_eq!(a.emitted, a.accounted(), "t = {}: {a:?}", sim.time());
    }
    let a = Accounts::of(sim.backend());
    assert!(a.on_ground > 10_000 && a.on_objects > 100 && a.left > 0, "{a:?}");
    // The depth channel is the count of each cell times the depth of a flake.
    let cover = *sim.model().sets.iter().find(|s| s.name == COVER).unwrap();
    let p = sim.read_set(&cover, &["snow_depth"]);
    let depth = p.channel("snow_depth").and_then(floe_proto::Values::as_scalars).unwrap();
    let per = sim.model().consts::<SnowfallConsts>().depth_per_flake;
    let total: f64 = depth.iter().map(|&d| f64::from(d)).sum();
    assert!((total / (a.on_ground as f64 * f64::from(per)) - 1.0).abs() < 1e-4);
}

/// The snow grid is a grid set with positions from its cells; the flakes a set of
/// their own.
#[test]
fn the_cover_and_the_flakes_are_sets() {
    let model = Model::build(&from_preset("snow_roof", &[]).unwrap()).unwrap();
    let sets: Vec<&str> = model.sets.iter().map(|s| s.name).collect();
    assert!(sets.contains(&FLAKES) && sets.contains(&COVER), "{sets:?}");
    let c = model.consts::<SnowfallConsts>();
    assert_eq!((c.nx, c.nz), (64, 16));
    assert_eq!(model.layout.count(CELLS), 64 * 16);
    assert_eq!(model.layout.count(FLAKES), c.capacity as usize);
    assert_eq!(model.particle_count(), 0);
}

/// The coverage channel: 0 in the house, 1 on the open floor, about cos(30
/// degrees) on the mountain side, and partial under the roof of `snow_roof`, where
/// the sky shows past its edges from some sampled directions only.
#[test]
fn coverage_follows_exposure_and_inclination() {
    let of = |attr: &'static str| {
        move |model: &Model, x: f32, z: f32| {
            let c = model.consts::<SnowfallConsts>();
            let column = model.layout.attrs.iter().find(|(s, _)| s.name == attr).map(|(_, c)| c);
            let Some(Column::F32(cover)) = column else { panic!("{attr}") };
            cover[flakes::cell(c, x, z)]
        }
    };
    let at = of(COVERAGE.name);
    let valley = Model::build(&from_preset("snowfall", &[]).unwrap()).unwrap();
    assert_eq!(at(&valley, 15.0, 7.0), 0.0, "inside the house");
    assert_eq!(at(&valley, 17.0, 2.0), 1.0, "the open floor");
    let slope = at(&valley, 5.0, 8.0);
    assert!((slope - 30f32.to_radians().cos()).abs() < 0.03, "the mountain side: {slope}");
    let roof = Model::build(&from_preset("snow_roof", &[]).unwrap()).unwrap();
    let under: Vec<f32> = [6.1, 7.0, 7.9].iter().map(|&x| at(&roof, x, 2.0)).collect();
    assert!(under.iter().all(|&f| f > 0.0 && f < 1.0) && under[1] < under[0], "under the roof: {under:?}");
    assert_eq!(at(&roof, 12.0, 2.0), 1.0);
    // The roof's own top sees the whole sky; open ground has no top.
    let top = of(TOP_COVERAGE.name);
    assert_eq!((top(&roof, 7.0, 2.0), top(&roof, 12.0, 2.0)), (1.0, 0.0));
}

/// The release on the CPU (the mountain side at 10 cm, released at 15 s): the snow
/// released is the particles' mass exactly (each particle a whole number of
/// flakes), the steep cells keep less than a particle's snow, the valley floor
/// keeps its cover, the flakes' accounting stays exact, and the avalanche runs.
#[test]
fn the_release_turns_the_cover_into_particles_mass_conserved() {
    let o = ["particle_spacing=0.1".to_string(), "snowfall.release.at=15".to_string()];
    let mut sim = crate::Simulation::new_cpu(from_preset("snowfall_then_avalanche", &o).unwrap()).unwrap();
    while sim.particle_count() == 0 {
        assert!(sim.time() < 15.5, "no release by {} s", sim.time());
        sim.step().unwrap();
    }
    let c = sim.model().consts::<SnowfallConsts>().clone();
    let r = c.release.clone().unwrap();
    assert!(sim.time() >= 15.0);
    let a = Accounts::of(sim.backend());
    assert_eq!(a.emitted, a.accounted(), "{a:?}");
    let n = sim.particle_count() as u64;
    assert_eq!(a.released, n * u64::from(r.flakes_per_particle), "{a:?}, {n} particles");
    let sph = n as f64 * f64::from(sim.model().materials.get(r.material as usize).mass);
    let released = a.released as f64 * r.flake_mass();
    assert!((sph / released - 1.0).abs() < 1e-6, "{sph} kg of particles from {released} kg of cover");
    let Column::U32(counts) = sim.backend().download(&[GROUND_COUNT.name]).remove(0) else { panic!() };
    assert!(r.cells.iter().all(|&k| counts[k as usize] < r.flakes_per_particle));
    let floor = flakes::cell(&c, 7.5, 1.0);
    assert!(!r.cells.contains(&(floor as u32)) && counts[floor] >= r.flakes_per_particle, "{}", counts[floor]);
    for _ in 0..20 {
        sim.step().unwrap();
    }
    assert_eq!(sim.particle_count() as u64, n, "released once");
}

/// A live intensity: raised to its maximum while it snows, the emission doubles
/// and the ring, the grid and a flake's snow stay as built; above the maximum it
/// is refused by path.
#[test]
fn the_intensity_changes_while_it_snows_up_to_its_maximum() {
    let o = ["snowfall.max_intensity={\"flakes_per_m2_s\":400}".to_string()];
    let mut sim = crate::Simulation::new_cpu(from_preset("snow_roof", &o).unwrap()).unwrap();
    let built = sim.model().consts::<SnowfallConsts>().clone();
    let rate = |sim: &mut crate::Simulation| {
        let (t0, e0) = (sim.time(), Accounts::of(sim.backend()).emitted);
        while sim.time() < t0 + 1.0 {
            sim.step().unwrap();
        }
        (Accounts::of(sim.backend()).emitted - e0) as f64 / (sim.time() - t0)
    };
    let light = rate(&mut sim);
    sim.set_parameters(&["snowfall.intensity={\"flakes_per_m2_s\":400}".into()]).unwrap();
    let heavy = rate(&mut sim);
    assert!(
        (light / (200.0 * 64.0) - 1.0).abs() < 1e-3 && (heavy / (400.0 * 64.0) - 1.0).abs() < 1e-3,
        "{light} {heavy}"
    );
    let now = sim.model().consts::<SnowfallConsts>();
    assert_eq!((now.capacity, now.depth_per_flake, now.nx), (built.capacity, built.depth_per_flake, built.nx));
    let a = Accounts::of(sim.backend());
    assert_eq!(a.emitted, a.accounted(), "{a:?}");
    let e = sim.set_parameters(&["snowfall.intensity={\"flakes_per_m2_s\":800}".into()]).unwrap_err().to_string();
    assert!(e.starts_with("snowfall.intensity: 800 flakes per m^2 per s is above max_intensity (400)"), "{e}");
}

/// A slab from an OBJ (1 x 0.1 x 1, fitted into a box 2 m wide: 2 x 0.2 x 2 m, 0.1
/// to 0.3 m up) on `snow_roof`'s open ground: the flakes over it land on its top,
/// none on the ground under it, and its cells' coverage is 0.
#[test]
fn a_mesh_is_an_object_flakes_land_on() {
    let slab = r#"snowfall.objects=[{"shape":"mesh","min":[11,0,1],"max":[13,0.4,3],"mesh":{"data_base64":"SLAB"}}]"#;
    let mut sim = crate::Simulation::new_cpu(from_preset("snow_roof", &[slab.replace("SLAB", SLAB)]).unwrap()).unwrap();
    while sim.time() < 6.0 {
        sim.step().unwrap();
    }
    let c = sim.model().consts::<SnowfallConsts>().clone();
    let cols = sim.backend().download(&[GROUND_COUNT.name, TOP_COUNT.name, COVERAGE.name]);
    let (Column::U32(ground), Column::U32(top), Column::F32(cover)) = (&cols[0], &cols[1], &cols[2]) else { panic!() };
    let under: Vec<usize> =
        [(11.4, 1.4), (12.0, 2.0), (12.6, 2.6)].iter().map(|&(x, z)| flakes::cell(&c, x, z)).collect();
    for &k in &under {
        assert!(
            top[k] > 0 && ground[k] == 0 && cover[k] == 0.0,
            "cell {k}: top {} ground {} coverage {}",
            top[k],
            ground[k],
            cover[k]
        );
    }
    let open = flakes::cell(&c, 15.0, 2.0);
    assert!(ground[open] > 0 && top[open] == 0 && cover[open] == 1.0);
    // Viewers draw the cover on the slab's top and on the open ground.
    let set = *sim.model().sets.iter().find(|s| s.name == COVER).unwrap();
    let p = sim.read_set(&set, &["cover_height", "cover_depth"]);
    let [height, depth] =
        ["cover_height", "cover_depth"].map(|n| p.channel(n).and_then(floe_proto::Values::as_scalars).unwrap());
    let per = c.depth_per_flake;
    for k in [under[1], open] {
        let (on, base) = if k == open { (ground[k], 0.0) } else { (top[k], 0.3) };
        assert!((depth[k] - on as f32 * per).abs() < 1e-6 && (height[k] - base - depth[k]).abs() < 1e-4, "cell {k}");
    }
    let a = Accounts::of(sim.backend());
    assert_eq!(a.emitted, a.accounted(), "{a:?}");
}

/// A slab 1 x 0.1 x 1 (OBJ, base64).
pub const SLAB: &str = "diAwIDAgMAp2IDEgMCAwCnYgMSAwIDEKdiAwIDAgMQp2IDAgMC4xIDAKdiAxIDAuMSAwCnYgMSAwLjEgMQp2IDAgMC4xIDEKZiAxIDIgMwpmIDEgMyA0CmYgNSA3IDYKZiA1IDggNwpmIDEgNSA2CmYgMSA2IDIKZiA0IDMgNwpmIDQgNyA4CmYgMSA0IDgKZiAxIDggNQpmIDIgNiA3CmYgMiA3IDMK";

/// Turbulence: bounded by its amplitude, smooth (points a hundredth of its scale
/// apart differ by a few hundredths of it), about zero on average and different
/// from place to place; a fall in it still accounts for every flake.
#[test]
fn turbulence_is_a_smooth_bounded_field() {
    let o = ["snowfall.turbulence={\"amplitude\":2,\"scale\":1,\"period\":2}".to_string()];
    let mut sim = crate::Simulation::new_cpu(from_preset("snow_roof", &o).unwrap()).unwrap();
    let c = sim.model().consts::<SnowfallConsts>().clone();
    let (mut sum, mut most, mut jump) = ([0.0f64; 2], 0.0f32, 0.0f32);
    let n = 4000;
    for k in 0..n {
        let (x, z, t) = (k as f32 * 0.37 % 16.0, k as f32 * 0.53 % 4.0, k as f32 * 0.011);
        let [a, b] = flakes::turbulence(&c, x, z, t);
        let [a2, b2] = flakes::turbulence(&c, x + 0.01, z, t);
        sum = [sum[0] + f64::from(a), sum[1] + f64::from(b)];
        most = most.max(a.abs()).max(b.abs());
        jump = jump.max((a2 - a).abs()).max((b2 - b).abs());
    }
    assert!(most <= 2.0 && most > 1.0, "largest component {most}");
    assert!(jump < 0.1, "a hundredth of the scale changes it by {jump}");
    assert!(sum.iter().all(|s| (s / n as f64).abs() < 0.2), "means {sum:?} / {n}");
    while sim.time() < 6.0 {
        sim.step().unwrap();
    }
    let a = Accounts::of(sim.backend());
    assert_eq!(a.emitted, a.accounted(), "{a:?}");
    assert!(a.on_ground > 0);
}
