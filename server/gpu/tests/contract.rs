//! A pass's data contract is declared once, in its `PassSpec` (what it reads,
//! writes and accumulates into), and every GPU kernel of it agrees: for every pass
//! of every preset's plan (and of variants that switch optional passes on), the
//! kernel binds each attribute the pass declares, binds no attribute it does not
//! declare, binds read-write only what the pass writes or accumulates into, and
//! binds nothing else but the core's buffers and the uniforms the backend makes.
//! Fused kernels bind what their passes declare together. Any kernel may read `x`,
//! where the GPU keeps the material index. No GPU is needed: the check is on the
//! declarations.

use floe_engine::model::Model;
use floe_engine::plan::PassSpec;
use floe_engine::scene::load::from_preset;
use floe_gpu::pass::{GpuPass, HOST_PASSES};
use floe_gpu::program::Access;

/// Buffers of the core a kernel may bind besides attributes (buffers.rs).
const CORE_BUFFERS: &[&str] = &["starts", "walls", "constraints"];
/// Uniforms of the core.
const CORE_UNIFORMS: &[&str] = &["params", "dt", "sweep"];

/// Every preset, and variants with the optional passes on.
fn scenes() -> Vec<(String, Model)> {
    let mut out = Vec::new();
    let variants: &[(&str, &[&str])] = &[
        ("dam_break", &["particle_spacing=0.05", "fluids[0].xsph=0.1"]),
        ("dam_break", &["particle_spacing=0.05", "solver.method=\"wcsph\"", "fluids[0].xsph=0.1"]),
        ("dam_break", &["particle_spacing=0.05", "solver.dfsph.solver=\"cg\""]),
        ("hydrostatic", &["particle_spacing=0.05", "solver.method=\"wcsph\""]),
        ("hydrostatic", &["particle_spacing=0.05", "solver.method=\"wcsph\"", "solver.delta_sph={\"delta\":0.1}"]),
        ("cross_channel", &["particle_spacing=0.1", r#"snow.solver={"method":"explicit"}"#]),
        ("elastic_drop", &["particle_spacing=0.04", "solid.oriented={}"]),
        ("elastic_drop", &["particle_spacing=0.04", "solid.stiffness_applied=\"once_per_step\""]),
        (
            "heated_channel",
            &[
                "particle_spacing=0.1",
                r#"modules=["fluid","heat","snow"]"#,
                r#"snow={"fluids":[{"model":"power_law","k":2000,"n":1.5}],"max_viscosity":3000}"#,
            ],
        ),
    ];
    for preset in floe_engine::scene::presets::names() {
        let build = |o: &[String]| from_preset(preset, o).ok().and_then(|s| Model::build(&s).ok());
        let model = build(&["particle_spacing=0.05".into()]).or_else(|| build(&[])).expect("every preset builds");
        out.push((preset.to_string(), model));
    }
    for (preset, overrides) in variants {
        let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        out.push((format!("{preset} {overrides:?}"), Model::build(&from_preset(preset, &o).unwrap()).unwrap()));
    }
    out
}

/// What is wrong with `kernel` as the GPU half of `passes` (one, or a fusion's) in `model`.
fn disagreements(model: &Model, passes: &[&PassSpec], kernel: &GpuPass) -> Vec<String> {
    let modules = floe_gpu::pass::uniforms().into_iter().map(|(n, _)| n);
    let uniforms: Vec<&str> = modules.chain(model.maps.iter().map(|m| m.name)).collect();
    let is_attr = |name: &str| model.layout.spec(name).is_some();
    let declared = |name: &str| passes.iter().any(|p| p.reads.contains(&name) || produces(p, name));
    let mut out = Vec::new();
    for &(access, name) in kernel.bindings {
        let problem = match access {
            Access::Uniform if !(CORE_UNIFORMS.contains(&name) || uniforms.contains(&name)) => {
                Some("binds a uniform the backend does not make")
            }
            Access::Uniform => None,
            _ if !is_attr(name) && !CORE_BUFFERS.contains(&name) => {
                Some("binds a buffer that is neither an attribute nor the core's")
            }
            // Any kernel may read positions: the GPU keeps each particle's material
            // index in the w of its position (the CPU's `material` attribute).
            Access::Read if name == "x" => None,
            // And a pass that changes particles' phase writes it there.
            Access::ReadWrite if name == "x" && passes.iter().any(|p| produces(p, "material")) => None,
            _ if is_attr(name) && !declared(name) => Some("binds an attribute its pass does not declare"),
            Access::ReadWrite if is_attr(name) && !passes.iter().any(|p| produces(p, name)) => {
                Some("binds read-write an attribute its pass only reads")
            }
            _ => None,
        };
        if let Some(p) = problem {
            out.push(format!("{} {p}: {name}", kernel.name));
        }
    }
    for p in passes {
        for &name in p.reads.iter().chain(p.writes).chain(p.accumulates) {
            // The material index rides in the w of each position on the GPU.
            let bound = kernel.bindings.iter().any(|&(_, b)| b == name) || (name == "material" && binds(kernel, "x"));
            if is_attr(name) && !bound {
                out.push(format!("{} does not bind {name}, which {} declares", kernel.name, p.name));
            }
        }
    }
    out
}

fn produces(p: &PassSpec, name: &str) -> bool {
    p.writes.contains(&name) || p.accumulates.contains(&name)
}

fn binds(kernel: &GpuPass, name: &str) -> bool {
    kernel.bindings.iter().any(|&(_, b)| b == name)
}

#[test]
fn every_gpu_kernel_binds_what_its_pass_declares() {
    let mut wrong = Vec::new();
    let mut checked = std::collections::BTreeSet::new();
    for (scene, model) in scenes() {
        for p in model.plan.passes() {
            if HOST_PASSES.contains(&p.name) {
                continue;
            }
            let Some(kernel) = floe_gpu::pass::find(p.name, &model) else {
                wrong.push(format!("{scene}: {} has no GPU kernel", p.name));
                continue;
            };
            wrong.extend(disagreements(&model, &[p], kernel).into_iter().map(|w| format!("{scene}: {w}")));
            checked.insert(p.name);
        }
        for fused in floe_gpu::pass::fused() {
            let passes: Vec<&PassSpec> = fused.passes.iter().filter_map(|n| model.plan.pass(n)).collect();
            if passes.len() == fused.passes.len() && (fused.kernel.when)(&model) {
                wrong
                    .extend(disagreements(&model, &passes, &fused.kernel).into_iter().map(|w| format!("{scene}: {w}")));
                checked.insert(fused.kernel.name);
            }
        }
    }
    // The core's passes around a position solve, whatever the presets hold: on a dam
    // break given the attribute they keep the predicted positions in.
    let (_, mut model) = scenes().remove(0);
    let p = &floe_engine::position_solve::X_PREDICTED;
    model.layout.attrs.push((p, floe_engine::attrs::Column::zeros(p.elem, model.particle_count())));
    for pass in [&floe_engine::position_solve::PREDICT, &floe_engine::position_solve::VELOCITY_FROM_POSITIONS] {
        let kernel = floe_gpu::pass::find(pass.name, &model).expect("a kernel");
        wrong.extend(disagreements(&model, &[pass], kernel).into_iter().map(|w| format!("position solve: {w}")));
        checked.insert(pass.name);
    }
    wrong.sort();
    wrong.dedup();
    assert!(wrong.is_empty(), "kernels against their passes' declarations:\n{}", wrong.join("\n"));
    // Every GPU kernel was checked in some scene.
    let all: Vec<&str> = floe_gpu::pass::all().iter().map(|k| k.name).collect();
    let unchecked: Vec<&&str> = all.iter().filter(|n| !checked.contains(*n)).collect();
    assert!(unchecked.is_empty(), "kernels no scene here runs: {unchecked:?}");
}

/// The check fails on each kind of disagreement.
#[test]
fn the_check_catches_a_kernel_that_strays_from_its_pass() {
    let model = Model::build(&from_preset("dam_break", &["particle_spacing=0.05".into()]).unwrap()).unwrap();
    let pass = model.plan.pass("fluid.forces").unwrap();
    let kernel = floe_gpu::pass::find("fluid.forces", &model).unwrap();
    assert!(disagreements(&model, &[pass], kernel).is_empty());
    let stray = |bindings: &'static [(Access, &'static str)]| {
        let k = GpuPass { bindings, ..*kernel };
        disagreements(&model, &[pass], &k)
    };
    use Access::{Read as R, ReadWrite as W, Uniform as U};
    let missing = stray(&[(U, "params"), (R, "x"), (R, "v"), (W, "a"), (R, "starts"), (R, "walls")]);
    assert!(missing.iter().any(|m| m.contains("does not bind rho")), "{missing:?}");
    let extra = stray(&[(U, "params"), (R, "x"), (R, "v"), (R, "rho"), (W, "a"), (R, "id")]);
    assert!(extra.iter().any(|m| m.contains("does not declare: id")), "{extra:?}");
    let rw = stray(&[(U, "params"), (R, "x"), (W, "v"), (R, "rho"), (W, "a")]);
    assert!(rw.iter().any(|m| m.contains("only reads: v")), "{rw:?}");
    let unknown = stray(&[(U, "params"), (U, "nope"), (R, "x"), (R, "v"), (R, "rho"), (W, "a"), (R, "cells")]);
    assert!(unknown.iter().any(|m| m.contains("uniform the backend does not make: nope")), "{unknown:?}");
    assert!(unknown.iter().any(|m| m.contains("neither an attribute nor the core's: cells")), "{unknown:?}");
}
