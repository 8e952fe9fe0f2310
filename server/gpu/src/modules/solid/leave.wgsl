// Per cluster of a melting body: which members hold (floe-engine
// `solid::cpu::Leave`, in the same order): 1 those of an elastic material (the
// material index in the w of x) that held, 2 (rejoining) those that did not but
// are within the cluster radius of the cluster's own particle, 0 the others;
// with fewer than solid.melt.z holding or rejoining the cluster dissolves.

@group(0) @binding(2) var<storage, read> start: array<u32>;
@group(0) @binding(3) var<storage, read> len: array<u32>;
@group(0) @binding(4) var<storage, read> member: array<u32>;
@group(0) @binding(5) var<storage, read> slot_of: array<u32>;
@group(0) @binding(6) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> owner: array<u32>;
@group(0) @binding(8) var<storage, read_write> live: array<u32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x) {
        return;
    }
    let origin = pos[slot_of[owner[s]]].xyz;
    let radius = bitcast<f32>(solid.melt.x);
    var held = 0u;
    for (var k = start[s]; k < start[s] + len[s]; k++) {
        let p = pos[slot_of[member[k]]];
        let elastic = ((solid.melt.y >> material_of(p)) & 1u) == 1u;
        let d = p.xyz - origin;
        var now = 0u;
        if (elastic && live[k] == 1u) {
            now = 1u;
        } else if (elastic && dot(d, d) <= radius * radius) {
            now = 2u;
        }
        live[k] = now;
        held += select(0u, 1u, now > 0u);
    }
    if (held < solid.melt.z) {
        for (var k = start[s]; k < start[s] + len[s]; k++) {
            live[k] = 0u;
        }
    }
}
