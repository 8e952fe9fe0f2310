// Per cluster: its live members and the mean of their rest offsets, 0 while
// all are live in a body that does not melt (solid.melt.w 0; floe-engine
// `solid::cpu::Live`, in the same order).

@group(0) @binding(2) var<storage, read> start: array<u32>;
@group(0) @binding(3) var<storage, read> len: array<u32>;
@group(0) @binding(4) var<storage, read> live: array<u32>;
@group(0) @binding(5) var<storage, read> rest: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> count: array<u32>;
@group(0) @binding(7) var<storage, read_write> rest_centre: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x) {
        return;
    }
    var held = 0u;
    var sum = vec3<f32>(0.0);
    for (var k = start[s]; k < start[s] + len[s]; k++) {
        if (live[k] == 1u) {
            held += 1u;
            sum += rest[k].xyz;
        }
    }
    count[s] = held;
    var centre = vec3<f32>(0.0);
    if ((solid.melt.w == 1u || held < len[s]) && held > 0u) {
        centre = sum / f32(held);
    }
    rest_centre[s] = vec4<f32>(centre, 0.0);
}
