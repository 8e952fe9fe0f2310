// Per membership, for every cluster: its member's position at the middle of the
// step, x - v dt / 2, relative to the cluster's own particle's, and its velocity
// (floe-engine `solid::cpu::Motion`).

// The stage's dt (s) in x; y, z, w are 0.
@group(0) @binding(10) var<uniform> dt: vec4<f32>;

@group(0) @binding(2) var<storage, read> member: array<u32>;
@group(0) @binding(3) var<storage, read> slot_of: array<u32>;
@group(0) @binding(4) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> segment: array<u32>;
@group(0) @binding(7) var<storage, read> owner: array<u32>;
@group(0) @binding(8) var<storage, read_write> relative: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> velocity: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let i = slot_of[member[k]];
    let o = slot_of[owner[segment[k]]];
    let back = 0.5 * dt.x;
    relative[k] = vec4<f32>((pos[i].xyz - vel[i].xyz * back) - (pos[o].xyz - vel[o].xyz * back), 0.0);
    velocity[k] = vec4<f32>(vel[i].xyz, 0.0);
}
