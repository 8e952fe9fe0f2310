//! Each GPU pass against the CPU backend (the oracle) on the same input.
//!
//! Both backends start from one CPU state 40 steps into a dam break (a moving,
//! splashing fluid against walls), so every term is non-trivial. Tolerances are
//! stated relative to each quantity's scale: the passes compute the same sums
//! in the same order, so only f32 rounding (fused multiply-adds on the GPU)
//! separates them.

mod common;

use floe_engine::backend::Backend;
use floe_engine::cpu::CpuBackend;
use floe_engine::guard::Measures;
use floe_engine::model::Model;
use floe_engine::quantize::PositionGrid;
use floe_engine::scene::load::from_preset;
use floe_engine::snapshot::{Reader, Writer};
use floe_engine::stepping::{Clock, Passes, SortedState};
use floe_gpu::GpuBackend;

/// A CPU and a GPU backend holding the same state, `steps` CPU steps into `preset`.
fn pair(gpu: &floe_gpu::GpuContext, preset: &str, overrides: &[&str], steps: usize) -> (CpuBackend, GpuBackend, Model) {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let model = Model::build(&from_preset(preset, &o).unwrap()).unwrap();
    let mut cpu = CpuBackend::new(model.clone());
    for _ in 0..steps {
        cpu.step().unwrap();
    }
    let mut w = Writer::default();
    cpu.save(&mut w);
    let mut g = GpuBackend::new(gpu, model.clone()).unwrap();
    g.load(&mut Reader::new(&w.0)).unwrap();
    (cpu, g, model)
}

fn state(b: &dyn Backend, model: &Model) -> SortedState {
    let mut w = Writer::default();
    b.save(&mut w);
    Clock::new(model).load(&mut Reader::new(&w.0), b.particle_count()).unwrap()
}

/// Largest `|a - b|` over components, and the largest `|a|` (the scale).
fn diff(a: &[glam::Vec3], b: &[glam::Vec3]) -> (f32, f32) {
    let d = a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f32::max);
    (d, a.iter().map(|x| x.abs().max_element()).fold(0.0, f32::max))
}

const VARIANTS: &[&[&str]] = &[
    &["particle_spacing=0.05"],
    &[
        "particle_spacing=0.05",
        "solver.kernel=\"mueller\"",
        "fluids[0].viscosity={\"model\":\"laplacian\",\"nu\":1e-3}",
        "fluids[0].xsph=0.3",
        "fluids[0].eos={\"kind\":\"linear\"}",
    ],
];

#[test]
fn sort_density_wall_pressure_forces_and_measures_match_the_cpu() {
    let Some(gpu) = common::gpu("sort_density_wall_pressure_forces_and_measures_match_the_cpu") else { return };
    for overrides in VARIANTS {
        let (mut cpu, mut g, model) = pair(gpu, "dam_break", overrides, 40);
        let (mc, mg): (Measures, Measures) = (cpu.evaluate().unwrap(), g.evaluate().unwrap());
        let (sc, sg) = (state(&cpu, &model), state(&g, &model));
        // The sort: both are stable counting sorts of the same order, so the
        // permutation (and the permuted state) is identical.
        assert_eq!(sc.ids, sg.ids, "{overrides:?}: sort order");
        assert_eq!(sc.pos, sg.pos, "{overrides:?}: sorted positions");
        assert_eq!(sc.vel, sg.vel, "{overrides:?}: sorted velocities");
        // Density: relative 1e-5 (rho ~ 1000 kg/m^3, ~30 neighbours).
        let (rc, rg) = (cpu.read(&["density"]), g.read(&["density"]));
        let (rc, rg) = (
            rc.channel("density").unwrap().as_scalars().unwrap(),
            rg.channel("density").unwrap().as_scalars().unwrap(),
        );
        let worst = rc.iter().zip(rg).map(|(a, b)| ((a - b) / a).abs()).fold(0.0, f32::max);
        assert!(worst < 1e-5, "{overrides:?}: density differs by {worst:e} (relative)");
        // Accelerations (pressure with wall pressures, viscosity, gravity):
        // 1e-4 of the largest. XSPH is checked through the kick below.
        let (d, scale) = diff(&sc.acc, &sg.acc);
        assert!(d <= 1e-4 * scale, "{overrides:?}: accelerations differ by {d:e} of {scale:e}");
        // Measures.
        assert_eq!(mc.max_speed2, mg.max_speed2, "{overrides:?}");
        assert!((mc.max_accel2 - mg.max_accel2).abs() <= 2e-4 * mc.max_accel2, "{overrides:?}: {mc:?} {mg:?}");
        assert!((mc.max_compression.0 - mg.max_compression.0).abs() < 1e-5, "{overrides:?}: {mc:?} {mg:?}");
        assert!(
            (mc.sum_compression - mg.sum_compression).abs() <= 1e-3 * mc.sum_compression.max(1e-6),
            "{mc:?} {mg:?}"
        );
        assert_eq!((mg.non_finite, mg.outside), (None, None));
    }
}

#[test]
fn kick_and_drift_match_the_cpu() {
    let Some(gpu) = common::gpu("kick_and_drift_match_the_cpu") else { return };
    for overrides in VARIANTS {
        let (mut cpu, mut g, model) = pair(gpu, "dam_break", overrides, 40);
        cpu.evaluate().unwrap();
        g.evaluate().unwrap();
        for p in [&mut cpu as &mut dyn PassesDyn, &mut g] {
            p.kick_drift(2e-3, 0.999);
        }
        g.flush();
        let (sc, sg) = (state(&cpu, &model), state(&g, &model));
        let (dv, vs) = diff(&sc.vel, &sg.vel);
        assert!(dv <= 1e-4 * vs.max(1.0), "{overrides:?}: velocities differ by {dv:e} (scale {vs})");
        let (dx, _) = diff(&sc.pos, &sg.pos);
        assert!(dx <= 1e-6, "{overrides:?}: positions differ by {dx:e} m");
    }
}

/// Kick (with XSPH and damping) then drift, through the shared pass interface.
trait PassesDyn {
    fn kick_drift(&mut self, dt: f32, keep: f32);
}

impl<P: Passes> PassesDyn for P {
    fn kick_drift(&mut self, dt: f32, keep: f32) {
        self.kick(dt, keep, true);
        self.drift(dt);
    }
}

#[test]
fn the_guard_finds_the_same_particle() {
    let Some(gpu) = common::gpu("the_guard_finds_the_same_particle") else { return };
    let (mut cpu, mut g, _) = pair(gpu, "dam_break", &["particle_spacing=0.05"], 10);
    let (mc, mg) = (cpu.evaluate().unwrap(), g.evaluate().unwrap());
    let id = |b: &mut dyn FnMut(u32) -> u32, slot| b(slot);
    assert_eq!(id(&mut |s| cpu.particle_id(s), mc.max_speed2.1), id(&mut |s| g.particle_id(s), mg.max_speed2.1));
}

#[test]
fn positions_quantised_on_the_gpu_match_the_cpu() {
    let Some(gpu) = common::gpu("positions_quantised_on_the_gpu_match_the_cpu") else { return };
    let (cpu, g, model) = pair(gpu, "dam_break", &["particle_spacing=0.05"], 40);
    let d = model.domain;
    let span = (d.max - d.min).max_element();
    for bits in [16, 10] {
        let grid = PositionGrid { min: d.min.to_array(), max: (d.min + glam::Vec3::splat(span)).to_array(), bits };
        let step = span / grid.top() as f32;
        let channels = ["density"];
        let (pc, pg) = (cpu.read_on_grid(&channels, &grid), g.read_on_grid(&channels, &grid));
        assert_eq!(pc.channel("density").map(|v| v.len()), pg.channel("density").map(|v| v.len()));
        assert_eq!(pc.positions.len(), pg.positions.len());
        // The same codes, except where a fused multiply-add on the GPU rounds a
        // value sitting on a code boundary the other way: then one step apart.
        let mut differ = 0;
        for (a, b) in pc.positions.iter().zip(&pg.positions) {
            for k in 0..3 {
                let codes = (grid.code(a[k], k), grid.code(b[k], k));
                assert!(codes.0.abs_diff(codes.1) <= 1, "{bits} bits: codes {codes:?}");
                differ += (codes.0 != codes.1) as usize;
            }
        }
        assert!(differ * 1000 <= 3 * pc.positions.len(), "{bits} bits: {differ} codes differ");
        // Positions only: the GPU copies back nothing but the codes.
        let only = g.read_on_grid(&[], &grid);
        assert_eq!(only.positions, pg.positions);
        assert!(only.channels.is_empty());
        let true_pos = g.read(&[]).positions;
        let worst = true_pos
            .iter()
            .zip(&only.positions)
            .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
            .fold(0.0, f32::max);
        assert!(worst <= 0.5 * step * 1.001, "{bits} bits: error {worst} m, half a step is {} m", 0.5 * step);
    }
}
