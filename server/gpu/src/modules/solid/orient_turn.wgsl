// Per membership: its cluster's rotation signed towards the member's previous
// orientation (QLERP), or the logarithm of its turn from it with w = 1, which
// counts the live memberships in the particle's sum (ExpMap) (floe-engine
// `solid::orient::Turn`).

@group(0) @binding(2) var<storage, read> rotation: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> segment: array<u32>;
@group(0) @binding(4) var<storage, read> member: array<u32>;
@group(0) @binding(5) var<storage, read> slot_of: array<u32>;
@group(0) @binding(6) var<storage, read> before: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> turn: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let r = rotation[segment[k]];
    let b = before[slot_of[member[k]]];
    if (solid.solver.z == 0u) {
        turn[k] = select(r, -r, dot(r, b) < 0.0);
    } else {
        turn[k] = vec4<f32>(quat_log(quat_short(quat_mul(r, quat_conj(b)))), 1.0);
    }
}
