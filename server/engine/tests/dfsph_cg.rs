//! DFSPH's conjugate-gradient solves (`solver.dfsph.solver = "cg"`) on the CPU: the
//! closed Poiseuille channel within the bound the Jacobi misses, the heated channel
//! within its bound, the periodic
//! Taylor-Green vortex past the step where the Jacobi diverges, the resting column
//! held with the walls mirrored (within its bound on Wendland's kernel), the start
//! from the fluid's weight, held particles
//! at zero stiffness, a settled column's surface held, the step a deep column's
//! pressure limits, a restore that continues bit for bit, and a scene of two
//! masses refused naming the setting.

use floe_engine::Simulation;
use floe_engine::attrs::Column;
use floe_engine::scene::load::from_preset;
use floe_engine::simulation::cpu_backend;
use floe_engine::validation::cases::{self, Variant};
use floe_engine::validation::hydrostatic;

/// The CG on the cubic spline (a test's own kernel, after these, wins).
const CG: [&str; 5] = [
    "solver.method=\"dfsph\"",
    "solver.dfsph.solver=\"cg\"",
    "solver.kernel=\"cubic_spline\"",
    "solver.delta_sph=null",
    "solver.transport_velocity=null",
];

fn overrides(extra: &[&str]) -> Vec<String> {
    CG.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn cg(preset: &str, extra: &[&str]) -> Simulation {
    Simulation::new_cpu(from_preset(preset, &overrides(extra)).unwrap()).unwrap()
}

/// The `poiseuille` case at the spacing its bounds are checked at (15 layers), as
/// `floe validate --bounds` runs it: within 1 % at 0.1 s, 0.5 s and steady, where the
/// Jacobi's steady profile is 7.8 % off (docs/validation/schemes/NOTES.md).
#[test]
fn the_closed_channel_reaches_the_poiseuille_profile() {
    let case = cases::all().into_iter().find(|c| c.name == "poiseuille").unwrap();
    let spacing = *case.spacings(false).last().unwrap();
    let variant = Variant { name: "cg", overrides: &[] };
    let out = cases::run(case, spacing, &variant, &overrides(&[]), &cpu_backend).unwrap();
    eprintln!("{out:?}");
    assert!(out.halted.is_none(), "{:?}", out.halted);
    for name in ["velocity_l2_t0_1", "velocity_l2_t0_5", "velocity_l2_steady"] {
        let e = out.error(name).unwrap();
        assert!(e <= 0.01, "{name} {e:.4}");
    }
}

/// The heated channel (a closed, periodic domain): within its bound where the
/// density's deviation unfiltered drove a pressure mode of alternating sign from 0.7 s
/// (velocity L2 2.4; `cg::RAW_EXCESS`).
#[test]
fn the_heated_channel_keeps_its_profile() {
    let case = cases::all().into_iter().find(|c| c.name == "heated_channel").unwrap();
    let spacing = *case.spacings(false).first().unwrap();
    let variant = Variant { name: "cg", overrides: &[] };
    let out = cases::run(case, spacing, &variant, &overrides(&[]), &cpu_backend).unwrap();
    eprintln!("{out:?}");
    assert!(out.halted.is_none(), "{:?}", out.halted);
    let e = out.error("velocity_l2").unwrap();
    assert!(e <= 0.03, "velocity L2 {e:.4}");
}

/// The `taylor_green` case (its preset: the CG, particles shifted in the closed box)
/// at the spacing its bounds are checked at, as `floe validate --bounds` runs it: the
/// decay rate within the case's 2 % (0.0045 measured; 0.57 unshifted, 0.0102 for
/// WCSPH with its transport velocity).
#[test]
fn the_shifted_vortex_decays_at_its_rate() {
    let case = cases::all().into_iter().find(|c| c.name == "taylor_green").unwrap();
    let spacing = case.checked_at.unwrap();
    let variant = Variant { name: "default", overrides: &[] };
    let out = cases::run(case, spacing, &variant, &[], &cpu_backend).unwrap();
    eprintln!("{out:?}");
    assert!(out.halted.is_none(), "{:?}", out.halted);
    let e = out.error("decay_rate_error").unwrap();
    assert!(e <= 0.02, "decay rate error {e:.4}");
}

/// The vortex's box is decided closed at its first step and no particle is held
/// after; the resting column (a free surface) is decided open.
#[test]
fn a_scene_is_decided_closed_or_open_at_its_first_step() {
    for (preset, extra, decided) in
        [("taylor_green", "particle_spacing=0.025", 1.0), ("hydrostatic", "particle_spacing=0.05", 2.0)]
    {
        let mut sim = cg(preset, &[extra]);
        let closed = |sim: &Simulation| match sim.backend().download(&["dfsph_closed"]).remove(0) {
            Column::F32(c) => c[0],
            c => panic!("{c:?}"),
        };
        assert_eq!(closed(&sim), 0.0, "{preset}: undecided before the first step");
        for _ in 0..10 {
            sim.step().unwrap();
            assert_eq!(closed(&sim), decided, "{preset}");
        }
        let held = match sim.backend().download(&["dfsph_held"]).remove(0) {
            Column::F32(h) => h.iter().sum::<f32>(),
            c => panic!("{c:?}"),
        };
        assert_eq!(held == 0.0, decided == 1.0, "{preset}: {held} particles held");
    }
}

/// The periodic vortex: the Jacobi's signed modes overshoot and it is NaN at step 2;
/// the CG converges every step.
#[test]
fn the_periodic_vortex_runs_and_its_solves_converge() {
    let mut sim = cg("taylor_green", &["particle_spacing=0.025"]);
    for _ in 0..20 {
        sim.step().unwrap();
    }
    let p = sim.read(&["velocity"]);
    let v = p.channel("velocity").and_then(|c| c.as_vectors()).unwrap();
    assert!(v.iter().flatten().all(|c| c.is_finite()));
    let solves = &sim.stats().solves;
    for name in ["dfsph.divergence", "dfsph.density"] {
        assert!(solves[name].last_residual <= 1e-3, "{name}: {solves:?}");
    }
}

/// The resting column on Wendland's kernel, whose arrangement stays a lattice under
/// the pressure (within a thousandth of a spacing of its layers in the bottom half,
/// where the cubic spline's column disorders by a tenth to a third of one): within
/// the case's bound of 2 % at its spacing (0.011 measured; the cubic spline 0.040),
/// and falling with the spacing over the case's quick ladder (0.0172, 0.0156, 0.0109
/// measured; 0.049 at 0.0375 m while the tank's walls stretched their lattice
/// against the fluid's).
#[test]
fn wendlands_kernel_holds_the_column_within_its_bound() {
    let column = |spacing: f64| {
        let at = format!("particle_spacing={spacing}");
        let mut sim = cg("hydrostatic", &[at.as_str(), "solver.kernel=\"wendland_c2\""]);
        sim.run_until(1.0, |_, _| {}).unwrap();
        let p = sim.read(&["density", "pressure"]);
        let e = hydrostatic::measure(&p, 1000.0, 9.81, 0.9, spacing);
        eprintln!("{spacing} m, {} steps: {e:?}", sim.steps());
        (e, p)
    };
    let coarser: Vec<f64> = [0.05, 0.0375].into_iter().map(|h| column(h).0.pressure_l2).collect();
    let spacing = 0.025;
    let (e, p) = column(spacing);
    assert!(
        coarser[0] > coarser[1] && coarser[1] > e.pressure_l2,
        "pressure L2 at 0.05, 0.0375, 0.025 m: {coarser:?}, {:.4}",
        e.pressure_l2
    );
    assert!(e.pressure_l2 < 0.02, "pressure L2 {:.4}", e.pressure_l2);
    assert!(e.mean_density_deviation < 0.01, "mean density deviation {:.4}", e.mean_density_deviation);
    let off = |y: f32| {
        let layers = y / spacing as f32 - 0.5;
        (layers - layers.round()).abs()
    };
    let bottom: Vec<f32> = p.positions.iter().map(|x| x[1]).filter(|&y| y < 0.45).map(off).collect();
    let mean = bottom.iter().sum::<f32>() / bottom.len() as f32;
    assert!(mean < 0.01, "mean distance from the layers {mean:.4} spacings");
}

/// The resting column with mirrored walls carrying the fluid's hydrostatic pressure,
/// at the spacing of the case's bounds: at its rest density, and its pressure within
/// 4.5 % of `rho0 g (H - y)` (0.040 measured at the steps the pressure limits, 0.050
/// with both solves converged to 1e-5 at the 5 ms cap; the bound of 0.02 is not met:
/// CG.md), against the Jacobi's 0.65, whose wall term needs twice the pressure beside
/// a wall.
#[test]
fn the_resting_column_is_held_with_mirrored_walls() {
    let column = |solver: &str| {
        let mut sim = cg("hydrostatic", &["particle_spacing=0.025", solver]);
        sim.run_until(1.0, |_, _| {}).unwrap();
        let p = sim.read(&["density", "pressure"]);
        let e = hydrostatic::measure(&p, 1000.0, 9.81, 0.9, 0.025);
        eprintln!("{solver}: {} steps: {e:?}, {:?}", sim.steps(), sim.stats().solves);
        e
    };
    let (cg, jacobi) = (column("solver.dfsph.solver=\"cg\""), column("solver.dfsph.solver=\"jacobi\""));
    assert!(cg.mean_density_deviation < 0.01, "mean density deviation {:.4}", cg.mean_density_deviation);
    assert!(cg.pressure_l2 < 0.045, "pressure L2 {:.3}", cg.pressure_l2);
    assert!(
        cg.pressure_l2 < 0.1 * jacobi.pressure_l2,
        "pressure L2 {:.3}, Jacobi {:.3}",
        cg.pressure_l2,
        jacobi.pressure_l2
    );
}

fn floats(sim: &Simulation, name: &str) -> Vec<f32> {
    let Column::F32(v) = sim.backend().download(&[name]).remove(0) else { panic!("{name}: a scalar attribute") };
    v
}

/// The CG's stiffness starts at the weight of the fluid above each particle,
/// `g (H - y) / rho0` for the column at rest (H its top layer's height plus half a
/// spacing); the Jacobi's at zero.
#[test]
fn the_stiffness_starts_under_the_fluid_s_weight() {
    let sim = cg("hydrostatic", &["particle_spacing=0.05"]);
    let (kappa, x) = (floats(&sim, "kappa"), sim.read(&[]).positions);
    let top = x.iter().map(|x| x[1]).fold(f32::MIN, f32::max) + 0.025;
    for (k, x) in kappa.iter().zip(&x) {
        let want = 9.81 * (top - x[1]) / 1000.0;
        assert!((k - want).abs() < 1e-6 * 9.81, "kappa {k} at y = {}, want {want}", x[1]);
    }
    let jacobi = cg("hydrostatic", &["particle_spacing=0.05", "solver.dfsph.solver=\"jacobi\""]);
    assert!(floats(&jacobi, "kappa").iter().all(|&k| k == 0.0));
}

/// A held particle (a free surface) is at zero stiffness after every step, whatever
/// it carried before: the dam break's front is held from its first step on, where
/// the start gave it the column's hydrostatic stiffness.
#[test]
fn held_particles_carry_no_stiffness() {
    let mut sim = cg("dam_break", &["particle_spacing=0.05"]);
    for step in 0..20 {
        sim.step().unwrap();
        let (kappa, held) = (floats(&sim, "kappa"), floats(&sim, "dfsph_held"));
        assert!(held.contains(&1.0) && held.contains(&0.0), "step {step}: a surface and a bulk");
        for (i, (k, h)) in kappa.iter().zip(&held).enumerate() {
            assert!(*h == 0.0 || *k == 0.0, "step {step}: held particle {i} at stiffness {k}");
        }
        assert!(kappa.iter().any(|&k| k > 0.0), "step {step}: the bulk carries the weight");
    }
}

/// A settled column keeps its free surface held: its top layer, pressed to 0.97-0.98
/// of the rest density, is held by its cut neighbourhood where the density test alone
/// let all of it go free, and the solves then took the column for a closed domain and
/// it burst (this column halted at 1.2 s, 96 % compression).
#[test]
fn a_settled_column_keeps_its_surface_held() {
    let mut sim = cg("hydrostatic", &["particle_spacing=0.025", "fluids[0].blocks[0].max=[0.3, 0.225, 0.15]"]);
    let mut fewest = usize::MAX;
    sim.run_until(2.0, |sim, _| {
        fewest = fewest.min(floats(sim, "dfsph_held").iter().filter(|&&h| h > 0.0).count());
    })
    .unwrap();
    assert!(fewest > 0, "no particle held at some step");
    let p = sim.read(&["velocity"]);
    let v = p.channel("velocity").and_then(|c| c.as_vectors()).unwrap();
    let fastest = v.iter().map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).fold(0.0, f32::max);
    eprintln!("fewest held {fewest}, fastest {fastest} m/s");
    assert!(fastest < 0.1, "a particle at {fastest:.3} m/s after 2 s at rest");
}

/// The CG's step is limited by the pressure's signal speed `sqrt(|p| / rho)`
/// (`timestep::Limits::c_p`): at 0.01875 m the column's 5 ms steps grow a disorder
/// from its floor within 0.05 s (pressure L2 3.8 at 0.04 s, 0.18 at 1 s); at
/// `0.5 h / c_p` it stays at rest (0.030 at 1 s).
#[test]
fn the_pressure_limits_the_step_of_a_deep_column() {
    let mut sim = cg("hydrostatic", &["particle_spacing=0.01875"]);
    let mut longest = 0.0f32;
    sim.run_until(1.0, |_, r| longest = longest.max(r.dt)).unwrap();
    let c_p = (floats(&sim, "kappa").iter().fold(0.0f32, |m, k| m.max(k.abs())) * 1000.0).sqrt();
    let p = sim.read(&["density", "pressure", "velocity"]);
    let e = hydrostatic::measure(&p, 1000.0, 9.81, 0.9, 0.01875);
    let v = p.channel("velocity").and_then(|c| c.as_vectors()).unwrap();
    let fastest = v.iter().map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).fold(0.0, f32::max);
    eprintln!("{} steps, longest {longest} s, c_p {c_p} m/s, fastest {fastest} m/s: {e:?}", sim.steps());
    assert!((2.9..3.3).contains(&c_p), "c_p {c_p} m/s against sqrt(g H) = 2.97");
    assert!(longest < 0.5 * 0.01875 / 2.9, "a step of {longest} s");
    assert!(e.pressure_l2 < 0.04, "pressure L2 {:.3}", e.pressure_l2);
    assert!(fastest < 0.15, "a particle at {fastest:.3} m/s");
}

#[test]
fn a_restored_snapshot_continues_bit_for_bit() {
    let mut a = cg("dam_break", &["particle_spacing=0.05"]);
    for _ in 0..15 {
        a.step().unwrap();
    }
    let mut b = Simulation::restore(&a.snapshot()).unwrap();
    for _ in 0..10 {
        assert_eq!(a.step().unwrap(), b.step().unwrap());
    }
    let all = ["velocity", "density", "pressure"];
    assert_eq!(a.read(&all), b.read(&all));
}

#[test]
fn a_scene_of_two_masses_is_refused_naming_the_setting() {
    let scene = from_preset("layers", &overrides(&["particle_spacing=0.025"])).unwrap();
    let e = Simulation::new_cpu(scene).unwrap_err().to_string();
    assert!(e.starts_with("solver.dfsph.solver: \"cg\" needs particles of one mass"), "{e}");
}
