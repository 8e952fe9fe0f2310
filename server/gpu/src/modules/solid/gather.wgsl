// x_k = x[member k] - x[the cluster's own particle] per membership of a cluster
// matched in this sweep (floe-engine `solid::cpu::GatherRelative`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> member: array<u32>;
@group(0) @binding(4) var<storage, read> slot_of: array<u32>;
@group(0) @binding(5) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> segment: array<u32>;
@group(0) @binding(7) var<storage, read> owner: array<u32>;
@group(0) @binding(8) var<storage, read> colour: array<u32>;
@group(0) @binding(9) var<storage, read_write> relative: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    if (!matched(colour[s], sweep.x)) {
        return;
    }
    let origin = pos[slot_of[owner[s]]].xyz;
    relative[k] = vec4<f32>(pos[slot_of[member[k]]].xyz - origin, 0.0);
}
