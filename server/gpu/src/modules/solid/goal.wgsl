// g_k = R q_k + c per membership (floe-engine `solid::cpu::Goal`).

@group(0) @binding(2) var<storage, read> rotation: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> centre: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> segment: array<u32>;
@group(0) @binding(5) var<storage, read> rest: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> goal: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    goal[k] = vec4<f32>(quat_rotate(rotation[s], rest[k].xyz) + centre[s].xyz, 0.0);
}
