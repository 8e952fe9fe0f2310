//! Every GPU pass against the CPU backend (the oracle), pass by pass from the
//! scene's plan: both backends reach the pass on their own, then get the CPU's
//! values of everything the pass reads, run the pass, and must agree on what it
//! writes within the pass's stated tolerance (relative to the largest magnitude).
//! The passes compute the same sums in the same order, so only f32 rounding
//! (fused multiply-adds on the GPU) separates them.
//!
//! Both backends start from one CPU state 40 steps into a dam break (a moving,
//! splashing fluid against walls), so every term is non-trivial; one variant is
//! periodic, so pairs across the periodic faces and the wrap are compared too, one
//! has a transport velocity, one integrates its density (δ-SPH), one is stepped by DFSPH, and one flows onto a terrain (its wall particles, and the
//! drift's heightfield constraint with friction). A solve's passes read scalars its
//! sums leave on the device: the oracle gives both backends the same test values.

#[path = "../common/mod.rs"]
mod common;
mod modules;

use floe_engine::Simulation;
use floe_engine::attrs::{Column, Elem, PARTICLES, WALLS};
use floe_engine::backend::Backend;
use floe_engine::model::Model;
use floe_engine::plan::{PassSpec, Stage};
use floe_engine::quantize::PositionGrid;
use floe_engine::scene::load::from_preset;
use floe_gpu::GpuBackend;

const WCSPH: &str = "solver.method=\"wcsph\"";

/// A CPU and a GPU simulation holding the same state, `steps` CPU steps into `preset`.
fn pair(gpu: &floe_gpu::GpuContext, preset: &str, overrides: &[&str], steps: usize) -> (Simulation, Simulation) {
    // WCSPH unless a variant names DFSPH after it: the dam break's preset uses DFSPH,
    // and most variants check WCSPH's passes.
    let o: Vec<String> = std::iter::once(WCSPH).chain(overrides.iter().copied()).map(String::from).collect();
    let mut cpu = Simulation::new_cpu(from_preset(preset, &o).unwrap()).unwrap();
    for _ in 0..steps {
        cpu.step().unwrap();
    }
    let bytes = cpu.snapshot();
    let gpu = gpu.clone();
    let on_gpu = move |model: Model| GpuBackend::new(&gpu, model).map(|b| Box::new(b) as Box<dyn Backend>);
    let g = Simulation::restore_on(&bytes, &on_gpu).unwrap();
    (Simulation::restore(&bytes).unwrap(), g)
}

/// Largest component difference and largest magnitude of two columns.
fn diff(a: &Column, b: &Column) -> (f64, f64) {
    let (wa, wb) = (a.words(), b.words());
    assert_eq!(wa.len(), wb.len());
    if let (Column::U32(x), Column::U32(y)) = (a, b) {
        let differ = x.iter().zip(y).filter(|(p, q)| p != q).count();
        return (differ as f64, 1.0);
    }
    let f = |w: &u32| f64::from(f32::from_bits(*w));
    let d = wa.iter().zip(&wb).map(|(p, q)| (f(p) - f(q)).abs()).fold(0.0, f64::max);
    (d, wa.iter().map(|p| f(p).abs()).fold(0.0, f64::max))
}

/// Compensated sums' carries and the attributes they carry for.
const CARRIES: &[(&str, &str)] = &[("temperature_carry", "temperature")];

/// Runs both backends up to `pass` (every earlier stage, then the earlier passes of
/// its stage), gives the GPU the CPU's values of what `pass` reads, runs it on both
/// and compares what it writes.
fn check_pass(cpu: &mut Simulation, gpu: &mut Simulation, pass: &'static PassSpec, label: &str) {
    for sim in [&mut *cpu, &mut *gpu] {
        let b = sim.backend_mut();
        for stage in Stage::ALL.iter().copied().filter(|s| *s < pass.stage) {
            b.run(stage, 1e-3);
        }
        let earlier: Vec<&str> =
            b.model().plan.stage(pass.stage).take_while(|p| p.name != pass.name).map(|p| p.name).collect();
        for p in earlier {
            b.run_pass(p, 1e-3);
        }
        b.end_step();
    }
    let inputs: Vec<&str> = pass.reads.iter().chain(pass.accumulates).copied().collect();
    // A solve's scalars are sums its iterations leave in a small space of their own
    // (never filled by a pass): both backends get the same test values.
    let written: Vec<&str> = cpu.model().plan.passes().iter().flat_map(|p| p.writes.iter().copied()).collect();
    for &name in &inputs {
        let spec = cpu.model().layout.spec(name).expect("a pass reads declared attributes");
        if spec.space != PARTICLES && spec.space != WALLS && spec.elem == Elem::F32 && !written.contains(&name) {
            let n = cpu.model().layout.count(spec.space);
            let values = Column::F32((0..n).map(|k| 0.5 + k as f32).collect());
            cpu.backend_mut().upload(name, values.clone());
            gpu.backend_mut().upload(name, values);
        }
    }
    for (name, column) in inputs.iter().zip(cpu.backend().download(&inputs)) {
        gpu.backend_mut().upload(name, column);
    }
    for sim in [&mut *cpu, &mut *gpu] {
        sim.backend_mut().run_pass(pass.name, 1e-3);
        sim.backend_mut().end_step();
    }
    let outputs: Vec<&str> = pass.writes.iter().chain(pass.accumulates).copied().collect();
    let (c, g) = (cpu.backend().download(&outputs), gpu.backend().download(&outputs));
    let column = |of: &[Column], name: &str| outputs.iter().position(|o| *o == name).map(|k| of[k].clone());
    for ((name, a), b) in outputs.iter().zip(&c).zip(&g) {
        // A compensated sum's carry is the rounding of its sum's last addition, which
        // differs wherever a GPU fuses a multiply and an add: what must agree is the
        // value the pair holds, sum - carry, on the sum's scale.
        let carried = CARRIES.iter().find(|(carry, _)| carry == name).and_then(|(_, sum)| {
            let less = |of: &[Column], carry: &Column| match (column(of, sum)?, carry) {
                (Column::F32(t), Column::F32(k)) => Some(Column::F32(t.iter().zip(k).map(|(t, k)| t - k).collect())),
                _ => None,
            };
            Some((less(&c, a)?, less(&g, b)?))
        });
        let (d, scale) = match &carried {
            Some((a, b)) => diff(a, b),
            None => diff(a, b),
        };
        let bound = f64::from(pass.tolerance) * scale.max(1e-12);
        assert!(
            d <= bound,
            "{label}: {} writes {name} {d:e} away from the CPU (scale {scale:e}, bound {bound:e})",
            pass.name
        );
    }
}

const VARIANTS: &[&[&str]] = &[
    &["particle_spacing=0.05"],
    &["particle_spacing=0.05", "modules=[\"fluid\",\"snowfall\"]", SNOWFALL],
    &[
        "particle_spacing=0.05",
        "solver.kernel=\"mueller\"",
        "fluids[0].viscosity={\"model\":\"laplacian\",\"nu\":1e-3}",
        "fluids[0].xsph=0.3",
        "fluids[0].eos={\"kind\":\"linear\",\"background\":500}",
    ],
    // Periodic along x (the collapsing column flows out through x = 0 and back in
    // at x = 2) and along z (a period of two cells: the block wraps onto itself).
    &[
        "particle_spacing=0.05",
        "periodic=[\"x\",\"z\"]",
        "boundaries[0].open=[\"-x\",\"+x\",\"-z\",\"+z\"]",
        "domain={\"min\":[0,-0.2,0],\"max\":[2,1.4,0.25]}",
    ],
    // The same with the transport velocity: its push, across periodic faces and
    // from the walls, and the drift that moves with it.
    &[
        "particle_spacing=0.05",
        "periodic=[\"x\",\"z\"]",
        "boundaries[0].open=[\"-x\",\"+x\",\"-z\",\"+z\"]",
        "domain={\"min\":[0,-0.2,0],\"max\":[2,1.4,0.25]}",
        "solver.transport_velocity={\"background\":20000}",
    ],
    // δ-SPH on two fluids (the diffusion between particles of one material only,
    // the heavy one's at its own speed of sound): the density's rate, walls
    // included, and its integration.
    &[
        "particle_spacing=0.05",
        TWO_FLUIDS,
        "fluids[1].eos={\"kind\":\"linear\",\"stiffness\":4900}",
        "solver.delta_sph={\"delta\":0.1}",
    ],
    // DFSPH: the factor and each solve's warm start, kick and error.
    &["particle_spacing=0.05", "solver.method=\"dfsph\""],
    // DFSPH by conjugate gradients: the held particles, each solve's warm start,
    // start, adjusted start, residual, step and clamp, the product and direction,
    // the mirrored walls in the factor and the kicks, and the walls' hydrostatic
    // pressure.
    &["particle_spacing=0.05", "solver.method=\"dfsph\"", "solver.dfsph.solver=\"cg\""],
    // The same on Wendland's kernel (its value and gradient in every pair loop).
    &[
        "particle_spacing=0.05",
        "solver.method=\"dfsph\"",
        "solver.dfsph.solver=\"cg\"",
        "solver.kernel=\"wendland_c2\"",
    ],
    // A rippled slope with friction across the tank under the column.
    &["particle_spacing=0.05", TERRAIN],
    // With heat: a hot corner of the column, a source, a flux through the left
    // wall, a floor held at 400 K and buoyancy; and with a second, denser fluid of other thermal properties and
    // buoyancy along its own g.
    &["particle_spacing=0.05", "modules=[\"fluid\",\"heat\"]", HEAT],
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"heat\"]",
        HEAT,
        TWO_FLUIDS,
        "heat.fluids=[{\"conductivity\":50,\"heat_capacity\":1000,\"expansion\":0.01,\"temperature\":300},\
          {\"conductivity\":5,\"heat_capacity\":500,\"expansion\":0.002,\"temperature\":280}]",
        "heat.buoyancy_gravity=[1,-5,0.5]",
    ],
    // With heat's viscosity laws: Arrhenius on one fluid (the implicit solve, the
    // default), and exponential and a table on two (the explicit force).
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"heat\"]",
        "fluids[0].viscosity={\"model\":\"none\"}",
        HEAT,
        "heat.fluids[0].viscosity={\"law\":\"arrhenius\",\"mu_ref\":5,\"t_ref\":300,\"activation_temperature\":2000}",
    ],
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"heat\"]",
        HEAT,
        TWO_FLUIDS,
        "fluids[0].viscosity={\"model\":\"none\"}",
        "fluids[1].viscosity={\"model\":\"none\"}",
        "heat.fluids=[{\"conductivity\":50,\"heat_capacity\":1000,\"temperature\":300,\
          \"viscosity\":{\"law\":\"exponential\",\"mu_ref\":2,\"t_ref\":300,\"b\":0.02}},\
          {\"conductivity\":5,\"heat_capacity\":500,\"temperature\":280,\
          \"viscosity\":{\"law\":\"table\",\"points\":[[250,8],[290,3],[330,1],[380,0.5],[420,0.4]]}}]",
        "heat.viscous_solver={\"method\":\"explicit\"}",
    ],
    // A temperature law scaling a snow rheology (the implicit solve): heat's shift
    // factor and the shear pass that applies it.
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"heat\",\"snow\"]",
        "fluids[0].viscosity={\"model\":\"none\"}",
        HEAT,
        "heat.fluids[0].viscosity={\"law\":\"arrhenius\",\"mu_ref\":5,\"t_ref\":300,\"activation_temperature\":2000}",
        "snow={\"fluids\":[{\"model\":\"cross\",\"mu_0\":20,\"mu_inf\":0.2,\"k\":2,\"n\":0.8}],\"max_viscosity\":50}",
    ],
    // With snow: each viscosity law, alone (the explicit force) and as two fluids of
    // different laws (the implicit solve, the default).
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"snow\"]",
        "snow={\"fluids\":[{\"model\":\"cross\",\"mu_0\":20,\"mu_inf\":0.2,\"k\":2,\"n\":0.8}],\"max_viscosity\":20,\
          \"solver\":{\"method\":\"explicit\"}}",
    ],
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"snow\"]",
        TWO_FLUIDS,
        "snow={\"fluids\":[{\"model\":\"carreau\",\"mu_0\":20,\"mu_inf\":1,\"lambda\":0.5,\"n\":0.4},\
          {\"model\":\"herschel_bulkley\",\"yield_stress\":5,\"k\":2,\"n\":0.6,\"m\":20}],\"max_viscosity\":50}",
    ],
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"snow\"]",
        TWO_FLUIDS,
        "snow={\"fluids\":[{\"model\":\"power_law\",\"k\":3,\"n\":0.7},\
          {\"model\":\"bingham\",\"yield_stress\":5,\"mu_p\":1,\"m\":20}],\"max_viscosity\":50}",
    ],
    // Implicit viscosity (each conjugate-gradient pass), two fluids, no-slip walls.
    &[
        "particle_spacing=0.05",
        "modules=[\"fluid\",\"snow\"]",
        TWO_FLUIDS,
        "snow={\"fluids\":[{\"model\":\"cross\",\"mu_0\":2000,\"mu_inf\":2,\"k\":2,\"n\":0.8},\
          {\"model\":\"newtonian\",\"mu\":50}],\"max_viscosity\":2000,\"solver\":{\"method\":\"implicit\"}}",
    ],
];

/// Snow falling into the dam break's tank, low enough that flakes land within the
/// oracle's 40 steps: on the floor, on a box and on a cylinder, in a gusting,
/// turbulent wind with flutter.
const SNOWFALL: &str = "snowfall={\"area\":{\"min\":[0,0],\"max\":[2,0.25]},\"height\":0.03,\"cell\":0.05,\
    \"flutter\":1,\"wind\":[0.5,0],\"gusts\":0.3,\"intensity\":{\"flakes_per_m2_s\":50000},\
    \"turbulence\":{\"amplitude\":0.3,\"scale\":0.2,\"period\":0.5},\
    \"objects\":[{\"shape\":\"box\",\"min\":[1.2,0,0],\"max\":[1.5,0.02,0.25]},\
    {\"shape\":\"cylinder\",\"centre\":[1.8,0.1],\"radius\":0.05,\"bottom\":0,\"top\":0.025}]}";

/// Two fluids: the dam break's column and a denser block beside it.
const TWO_FLUIDS: &str = "fluids=[{\"blocks\":[{\"min\":[0,0,0],\"max\":[0.5,1,0.25]}]},\
    {\"name\":\"heavy\",\"rest_density\":3000,\"blocks\":[{\"min\":[1.2,0,0],\"max\":[1.7,0.5,0.25]}]}]";

/// The tank of the dam break with a terrain inside, under the collapsing column.
const TERRAIN: &str = "boundaries=[{\"kind\":\"box\",\"min\":[0,0,0],\"max\":[2,1.2,0.25]},\
    {\"kind\":\"terrain\",\"min\":[0,0],\"max\":[2,0.25],\"friction\":0.5,\"layers\":2,\
    \"heights\":{\"source\":\"slope\",\"top\":0.4,\"angle\":25,\"ripple\":0.05,\"wavelength\":0.2}}]";

/// The heat section of the oracle's heat variants.
const HEAT: &str = "heat={\"fluids\":[{\"conductivity\":50,\"heat_capacity\":1000,\"expansion\":0.01,\"temperature\":300}],\
    \"regions\":[{\"min\":[0,0,0],\"max\":[0.3,0.3,0.25],\"temperature\":350}],\
    \"walls\":[{\"min\":[-1,-1,-1],\"max\":[3,0,1],\"temperature\":400}],\
    \"sources\":[{\"min\":[0,0.5,0],\"max\":[0.5,1,0.25],\"power\":1e7}],\
    \"fluxes\":[{\"min\":[-1,-1,-1],\"max\":[0,2,1],\"flux\":5e5}]}";

#[test]
fn every_pass_of_the_plan_matches_the_cpu() {
    let Some(gpu) = common::gpu("every_pass_of_the_plan_matches_the_cpu") else { return };
    for overrides in VARIANTS {
        let (cpu, _) = pair(gpu, "dam_break", overrides, 40);
        let passes: Vec<&'static PassSpec> = cpu.model().plan.passes().to_vec();
        for pass in passes.into_iter().filter(|p| p.name != "core.sort") {
            let (mut cpu, mut g) = pair(gpu, "dam_break", overrides, 40);
            check_pass(&mut cpu, &mut g, pass, &format!("{overrides:?}"));
        }
    }
}

/// A fused kernel (several passes of a stage in one neighbour walk) against the
/// CPU's passes: both backends reach the stage on their own, the GPU gets the CPU's
/// values of everything the stage reads, both run the whole stage (the GPU with
/// its fused kernels, as in a step) and must agree on everything it writes, each
/// output within the tolerance of the pass writing it.
fn check_fused_stage(cpu: &mut Simulation, gpu: &mut Simulation, stage: Stage, label: &str) {
    for sim in [&mut *cpu, &mut *gpu] {
        let b = sim.backend_mut();
        for earlier in Stage::ALL.iter().copied().filter(|s| *s < stage) {
            b.run(earlier, 1e-3);
        }
        b.end_step();
    }
    let passes: Vec<&'static PassSpec> = cpu.model().plan.stage(stage).collect();
    let mut inputs: Vec<&str> = passes.iter().flat_map(|p| p.reads.iter().chain(p.accumulates)).copied().collect();
    inputs.sort_unstable();
    inputs.dedup();
    for (name, column) in inputs.iter().zip(cpu.backend().download(&inputs)) {
        gpu.backend_mut().upload(name, column);
    }
    for sim in [&mut *cpu, &mut *gpu] {
        sim.backend_mut().run(stage, 1e-3);
        sim.backend_mut().end_step();
    }
    for pass in passes {
        let outputs: Vec<&str> = pass.writes.iter().chain(pass.accumulates).copied().collect();
        let (c, g) = (cpu.backend().download(&outputs), gpu.backend().download(&outputs));
        for ((name, a), b) in outputs.iter().zip(&c).zip(&g) {
            let (d, scale) = diff(a, b);
            let bound = f64::from(pass.tolerance) * scale.max(1e-12);
            assert!(d <= bound, "{label}: {name} ({}) is {d:e} away from the CPU (bound {bound:e})", pass.name);
        }
    }
}

#[test]
fn fused_kernels_match_the_cpu() {
    let Some(gpu) = common::gpu("fused_kernels_match_the_cpu") else { return };
    let mut fused = 0;
    for overrides in VARIANTS {
        let (cpu, _) = pair(gpu, "dam_break", overrides, 40);
        for (kernel, covers) in floe_gpu::pass::fusions(cpu.model(), gpu.max_storage_buffers()) {
            let stage = cpu.model().plan.passes()[covers[0]].stage;
            let (mut cpu, mut g) = pair(gpu, "dam_break", overrides, 40);
            check_fused_stage(&mut cpu, &mut g, stage, &format!("{} {overrides:?}", kernel.kernel.name));
            fused += 1;
        }
    }
    // The heat variants under WCSPH fuse the force pass with conduction wherever a
    // device binds their ten storage buffers (lavapipe, and desktop GPUs, bind far more).
    if gpu.max_storage_buffers() >= floe_gpu::modules::fused::FORCES_AND_CONDUCTION.storage_buffers() {
        assert!(fused >= 2, "{fused} fused stages checked");
    }
}

#[test]
fn the_sort_gives_the_same_order_and_one_step_runs_the_plan_in_order() {
    let Some(gpu) = common::gpu("the_sort_gives_the_same_order_and_one_step_runs_the_plan_in_order") else { return };
    for overrides in VARIANTS {
        let (mut cpu, mut g) = pair(gpu, "dam_break", overrides, 40);
        for sim in [&mut cpu, &mut g] {
            sim.backend_mut().run(Stage::Sort, 0.0);
            sim.backend_mut().end_step();
        }
        // Both are stable counting sorts of the same order: identical permutations.
        let names = ["id", "x", "v", "a", "slot_of"];
        assert_eq!(cpu.backend().download(&names), g.backend().download(&names), "{overrides:?}");
        cpu.step().unwrap();
        g.step().unwrap();
        // The CG's shift runs in a closed scene only (the dam break is open).
        let closed_only: Vec<&str> = floe_engine::schemes::dfsph::cg::SHIFT_PASSES.iter().map(|p| p.name).collect();
        let plan: Vec<&str> =
            cpu.model().plan.passes().iter().map(|p| p.name).filter(|n| !closed_only.contains(n)).collect();
        assert_eq!(cpu.backend().passes_run(), plan, "{overrides:?}: CPU");
        assert_eq!(g.backend().passes_run(), plan, "{overrides:?}: GPU");
    }
}

#[test]
fn measures_kick_and_drift_match_the_cpu() {
    let Some(gpu) = common::gpu("measures_kick_and_drift_match_the_cpu") else { return };
    for overrides in VARIANTS {
        let (mut cpu, mut g) = pair(gpu, "dam_break", overrides, 40);
        let mut measures = Vec::new();
        for sim in [&mut cpu, &mut g] {
            let b = sim.backend_mut();
            for stage in [Stage::Sort, Stage::Density, Stage::PreForce, Stage::Force] {
                b.run(stage, 0.0);
            }
            measures.push(b.measure().unwrap());
        }
        let (mc, mg) = (measures[0], measures[1]);
        assert_eq!(mc.max_speed2, mg.max_speed2, "{overrides:?}");
        assert!((mc.max_accel2 - mg.max_accel2).abs() <= 2e-4 * mc.max_accel2, "{overrides:?}: {mc:?} {mg:?}");
        assert!((mc.max_compression.0 - mg.max_compression.0).abs() < 1e-5, "{overrides:?}: {mc:?} {mg:?}");
        assert!(
            (mc.sum_compression - mg.sum_compression).abs() <= 1e-3 * mc.sum_compression.max(1e-6),
            "{mc:?} {mg:?}"
        );
        assert_eq!((mg.non_finite, mg.outside), (None, None));
        // The guard names the same particle.
        let id = |sim: &mut Simulation| sim.backend_mut().particle_id(mc.max_speed2.1);
        assert_eq!(id(&mut cpu), id(&mut g));
        // Kick (with damping) and drift from the same accelerations.
        let moved: &[&str] =
            if cpu.model().layout.spec("a_transport").is_some() { &["a", "a_transport"] } else { &["a"] };
        for (name, column) in moved.iter().zip(cpu.backend().download(moved)) {
            g.backend_mut().upload(name, column);
        }
        for sim in [&mut cpu, &mut g] {
            let b = sim.backend_mut();
            b.kick(2e-3, 0.999);
            b.drift(2e-3);
            b.end_step();
        }
        let (dv, vs) = diff(&cpu.backend().download(&["v"])[0], &g.backend().download(&["v"])[0]);
        assert!(dv <= 1e-4 * vs.max(1.0), "{overrides:?}: velocities differ by {dv:e} (scale {vs})");
        let (dx, _) = diff(&cpu.backend().download(&["x"])[0], &g.backend().download(&["x"])[0]);
        assert!(dx <= 1e-6, "{overrides:?}: positions differ by {dx:e} m");
    }
}

#[test]
fn reductions_match_the_cpu() {
    let Some(gpu) = common::gpu("reductions_match_the_cpu") else { return };
    use floe_engine::scheme::{ReduceOp, Reduction};
    let (mut cpu, mut g) = pair(gpu, "dam_break", &["particle_spacing=0.05"], 40);
    for sim in [&mut cpu, &mut g] {
        sim.backend_mut().run(Stage::Sort, 0.0);
        sim.backend_mut().run(Stage::Density, 0.0);
    }
    let outside = ReduceOp::Outside { min: 999.0, max: 1001.0 };
    for op in [ReduceOp::Sum, ReduceOp::Mean, ReduceOp::Norm, ReduceOp::Max, ReduceOp::MaxAbs, outside] {
        let r = Reduction { attr: "rho", op };
        let (c, v) = (cpu.backend_mut().reduce(&r).unwrap(), g.backend_mut().reduce(&r).unwrap());
        assert!((c - v).abs() <= 1e-5 * c.abs(), "{op:?}: CPU {c}, GPU {v}");
    }
}

/// A sum a solve keeps on the device lands in the slot it names, as on the CPU.
#[test]
fn sums_into_a_solves_scalars_match_the_cpu() {
    let Some(gpu) = common::gpu("sums_into_a_solves_scalars_match_the_cpu") else { return };
    let (mut cpu, mut g) = pair(gpu, "cross_channel", &["particle_spacing=0.1", IMPLICIT], 5);
    let mut scalars = Vec::new();
    for sim in [&mut cpu, &mut g] {
        let b = sim.backend_mut();
        b.run(Stage::Sort, 0.0);
        b.run(Stage::Density, 0.0);
        b.sum_into("rho", "visc_scalars", 2);
        b.end_step();
        scalars.push(b.download(&["visc_scalars"]).remove(0));
    }
    let (Column::F32(c), Column::F32(v)) = (&scalars[0], &scalars[1]) else { panic!("f32 scalars") };
    assert!(c[2] > 0.0 && (c[2] - v[2]).abs() <= 1e-5 * c[2], "CPU {c:?}, GPU {v:?}");
    assert_eq!((c[0], c[1], c[3]), (v[0], v[1], v[3]), "the other slots are untouched");
}

/// The implicit viscosity solve of the channel presets.
const IMPLICIT: &str = "snow.solver={\"method\":\"implicit\"}";

/// Whole steps with implicit viscosity (a stiff Cross fluid, 1e4 between its
/// viscosities, at 100 times the explicit limit on dt): the GPU's solve takes as
/// many iterations as the CPU's, to the same residual, and the velocities agree.
#[test]
fn implicit_viscosity_steps_like_the_cpu() {
    let Some(gpu) = common::gpu("implicit_viscosity_steps_like_the_cpu") else { return };
    let stiff = ["snow.fluids[0].mu_0=3e4", "snow.fluids[0].mu_inf=3", "snow.max_viscosity=3e4"];
    let overrides = [&["particle_spacing=0.1", IMPLICIT][..], &stiff].concat();
    let (mut cpu, mut g) = pair(gpu, "cross_channel", &overrides, 5);
    for _ in 0..20 {
        let (rc, rg) = (cpu.step().unwrap(), g.step().unwrap());
        let limit = cpu.measures().into_iter().find(|m| m.name == "snow.explicit_dt_limit").unwrap().value;
        assert!(f64::from(rc.dt) > 100.0 * limit, "dt {} against the explicit limit {limit}", rc.dt);
        let (sc, sg) = (rc.solves[0], rg.solves[0]);
        assert!(sc.iterations.abs_diff(sg.iterations) <= 1, "iterations: CPU {sc:?}, GPU {sg:?}");
        assert!(sc.residual <= 1e-3 && sg.residual <= 1e-3, "CPU {sc:?}, GPU {sg:?}");
    }
    let (d, scale) = diff(&cpu.backend().download(&["v"])[0], &g.backend().download(&["v"])[0]);
    assert!(scale > 0.0 && d <= 2e-3 * scale, "velocities differ by {d:e} (scale {scale:e})");
}

#[test]
fn positions_quantised_on_the_gpu_match_the_cpu() {
    let Some(gpu) = common::gpu("positions_quantised_on_the_gpu_match_the_cpu") else { return };
    let (cpu, g) = pair(gpu, "dam_break", &["particle_spacing=0.05"], 40);
    let d = cpu.domain();
    let span = (d.max - d.min).max_element();
    let set = floe_engine::channels::PARTICLE_SET;
    for bits in [16, 10] {
        let grid = PositionGrid { min: d.min.to_array(), max: (d.min + glam::Vec3::splat(span)).to_array(), bits };
        let step = span / grid.top() as f32;
        let channels = ["density"];
        let (pc, pg) = (cpu.read_on_grid(&set, &channels, &grid), g.read_on_grid(&set, &channels, &grid));
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
        let only = g.read_on_grid(&set, &[], &grid);
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
