// Per cluster matched in this sweep: its rotation and the origin of its goals,
// the live members' centre less their rotated rest centre, with the cluster's
// share of its ways in w (floe-engine `solid::cpu::Rotate`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> moment: array<mat3x3<f32>>;
@group(0) @binding(4) var<storage, read> cluster_sum: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> live: array<u32>;
@group(0) @binding(6) var<storage, read> rest_centre: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> colour: array<u32>;
@group(0) @binding(8) var<storage, read> share: array<f32>;
@group(0) @binding(9) var<storage, read_write> centre: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> rotation: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x || !matched(colour[s], sweep.x)) {
        return;
    }
    var q: vec4<f32>;
    if (solid.sizes.z == 0u) {
        q = polar_iterative(moment[s], rotation[s], solid.sizes.w);
    } else {
        q = polar_eigen(moment[s]);
    }
    rotation[s] = q;
    centre[s] = vec4<f32>(cluster_sum[s].xyz / f32(max(live[s], 1u)) - quat_rotate(q, rest_centre[s].xyz), share[s]);
}
