// Boussinesq buoyancy (floe-engine `modules::heat::passes`): a += -beta (T - T0) g.

@group(0) @binding(1) var<uniform> heat: Heat;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> temperature: array<f32>;
@group(0) @binding(4) var<storage, read_write> acc: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let beta = heat.material[material_of(pos[i])].z;
    acc[i] = vec4<f32>(acc[i].xyz - heat.gravity.xyz * (beta * (temperature[i] - heat.reference)), 0.0);
}
