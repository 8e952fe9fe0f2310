// Per cluster: adds its live members' ellipsoid moments R D to its moment
// (floe-engine `solid::orient::Ellipsoid`).

@group(0) @binding(2) var<storage, read> start: array<u32>;
@group(0) @binding(3) var<storage, read> len: array<u32>;
@group(0) @binding(4) var<storage, read> live: array<u32>;
@group(0) @binding(5) var<storage, read> member: array<u32>;
@group(0) @binding(6) var<storage, read> slot_of: array<u32>;
@group(0) @binding(7) var<storage, read> orientation: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> moment: array<mat3x3<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x) {
        return;
    }
    let d = solid.settings.yzw;
    var m = moment[s];
    for (var k = start[s]; k < start[s] + len[s]; k++) {
        if (live[k] != 0u) {
            let r = quat_mat(orientation[slot_of[member[k]]]);
            m += mat3x3<f32>(r[0] * d.x, r[1] * d.y, r[2] * d.z);
        }
    }
    moment[s] = m;
}
