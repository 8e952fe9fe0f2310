// Per cluster matched in this sweep: its centre and rotation (floe-engine
// `solid::cpu::Rotate`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> moment: array<mat3x3<f32>>;
@group(0) @binding(4) var<storage, read> cluster_sum: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> len: array<u32>;
@group(0) @binding(6) var<storage, read> colour: array<u32>;
@group(0) @binding(7) var<storage, read_write> centre: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> rotation: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x || !matched(colour[s], sweep.x)) {
        return;
    }
    centre[s] = vec4<f32>(cluster_sum[s].xyz / f32(len[s]), 0.0);
    if (solid.sizes.z == 0u) {
        rotation[s] = polar_iterative(moment[s], rotation[s], solid.sizes.w);
    } else {
        rotation[s] = polar_eigen(moment[s]);
    }
}
