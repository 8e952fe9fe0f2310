// Per membership: its angular momentum r x v and inertia |r|^2 1 - r r^T about
// its cluster's centre, per unit mass (floe-engine `solid::cpu::Spin`).

@group(0) @binding(2) var<storage, read> relative: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> cluster_sum: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> live: array<u32>;
@group(0) @binding(5) var<storage, read> segment: array<u32>;
@group(0) @binding(6) var<storage, read> velocity: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> spin: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> inertia: array<mat3x3<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    let r = relative[k].xyz - cluster_sum[s].xyz / f32(max(live[s], 1u));
    spin[k] = vec4<f32>(cross(r, velocity[k].xyz), 0.0);
    inertia[k] = inertia_of(r);
}
