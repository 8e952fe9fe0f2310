//! Every WGSL kernel (the core's and every plan pass's) parses and validates with
//! naga, without any GPU, and no entry point binds more than 8 storage buffers: the
//! portability floor this project keeps (WebGPU's default limit). A module that
//! needs more splits its pass; module constants go in uniforms, which do not count.
//! A fused kernel (several passes in one walk) may bind more, as the backend uses it
//! only on devices that allow it; each pass it does has a kernel within the floor.

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

/// Storage buffers a kernel may bind.
const STORAGE_BUDGET: usize = 8;

fn validate(name: &str, source: &str) -> (naga::Module, ModuleInfo) {
    let module =
        naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    let info = Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    assert!(!module.entry_points.is_empty(), "{name} has no entry point");
    (module, info)
}

/// Storage buffers each entry point of `module` uses, by entry point name.
fn storage_bindings(module: &naga::Module, info: &ModuleInfo) -> Vec<(String, usize)> {
    module
        .entry_points
        .iter()
        .enumerate()
        .map(|(i, ep)| {
            let uses = info.get_entry_point(i);
            let count = module
                .global_variables
                .iter()
                .filter(|(h, g)| matches!(g.space, naga::AddressSpace::Storage { .. }) && !uses[*h].is_empty())
                .count();
            (ep.name.clone(), count)
        })
        .collect()
}

#[test]
fn every_shader_validates_and_binds_at_most_8_storage_buffers() {
    let core = floe_gpu::passes::SOURCES.iter().map(|&(name, source)| (name, source));
    let plan = floe_gpu::pass::all().into_iter().map(|p| (p.name, p.source));
    let mut checked = 0;
    for (name, source) in core.chain(plan) {
        let (module, info) = validate(name, source);
        for (entry, count) in storage_bindings(&module, &info) {
            assert!(
                count <= STORAGE_BUDGET,
                "{name}::{entry} binds {count} storage buffers, more than {STORAGE_BUDGET}"
            );
        }
        checked += 1;
    }
    assert!(checked >= 14, "{checked} shaders");
}

#[test]
fn fused_kernels_validate_and_bind_what_they_declare() {
    for fused in floe_gpu::pass::fused() {
        let k = &fused.kernel;
        let (module, info) = validate(k.name, k.source);
        for (entry, count) in storage_bindings(&module, &info) {
            assert_eq!(count as u32, fused.storage_buffers(), "{}::{entry}", k.name);
        }
        assert_eq!(k.name, fused.passes.join("+"));
        for pass in fused.passes {
            assert!(
                floe_gpu::pass::all().iter().any(|p| p.name == *pass),
                "{pass}, fused in {}, has no kernel",
                k.name
            );
        }
    }
}

#[test]
fn the_budget_check_counts_what_a_kernel_uses() {
    // Nine storage buffers, eight of them used: within the budget.
    let declare = (0..9).map(|k| format!("@group(0) @binding({k}) var<storage, read_write> b{k}: array<f32>;\n"));
    let body = (0..8).map(|k| format!("    b{k}[0] = 1.0;\n")).collect::<String>();
    let source = format!("{}@compute @workgroup_size(1)\nfn main() {{\n{body}}}\n", declare.collect::<String>());
    let (module, info) = validate("budget", &source);
    assert_eq!(storage_bindings(&module, &info), [("main".to_string(), 8)]);
    let nine = source.replace("    b0[0] = 1.0;\n", "    b0[0] = 1.0;\n    b8[0] = 1.0;\n");
    let (module, info) = validate("budget", &nine);
    assert_eq!(storage_bindings(&module, &info), [("main".to_string(), 9)]);
}

#[test]
fn every_plan_pass_of_the_cpu_has_a_gpu_half_and_the_other_way_round() {
    let gpu: Vec<&str> = floe_gpu::pass::all().iter().map(|p| p.name).collect();
    let cpu = floe_engine::cpu::implementations();
    for name in &gpu {
        assert!(cpu.contains(name), "GPU pass {name} has no CPU half");
    }
    for name in &cpu {
        // The sort is the core's own sequence of kernels on the GPU; the neighbour search is done in every pass.
        assert!(gpu.contains(name) || floe_gpu::pass::HOST_PASSES.contains(name), "CPU pass {name} has no GPU half");
    }
}
