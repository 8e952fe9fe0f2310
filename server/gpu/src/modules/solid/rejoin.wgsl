// A member rejoining its cluster (live 2) takes as its rest offset where it was
// at the end of the last step in the cluster's frame, R^T (x - o), o the origin of
// the cluster's goals (floe-engine `solid::cpu::Rejoin`).

@group(0) @binding(2) var<storage, read> member_x: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> segment: array<u32>;
@group(0) @binding(4) var<storage, read> rotation: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> centre: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> rest: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> live: array<u32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y || live[k] != 2u) {
        return;
    }
    let s = segment[k];
    let q = rotation[s];
    rest[k] = vec4<f32>(quat_rotate(vec4<f32>(-q.xyz, q.w), member_x[k].xyz - centre[s].xyz), 0.0);
    live[k] = 1u;
}
