// Per membership: its member's velocity under its cluster's rigid motion,
// v_c + omega x r, weight 1 (floe-engine `solid::cpu::RigidWay`).

@group(0) @binding(2) var<storage, read> relative: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> cluster_sum: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> live: array<u32>;
@group(0) @binding(5) var<storage, read> segment: array<u32>;
@group(0) @binding(6) var<storage, read> mean: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> omega: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> way: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> weight: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    let r = relative[k].xyz - cluster_sum[s].xyz / f32(max(live[s], 1u));
    way[k] = vec4<f32>(mean[s].xyz + cross(omega[s].xyz, r), 0.0);
    weight[k] = 1.0;
}
