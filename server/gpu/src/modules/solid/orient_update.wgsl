// Per particle of a body: the blend of its turns over its live clusters is its
// orientation, and the turn from the one before its angular velocity; a melted
// particle keeps its orientation and stops turning (floe-engine
// `solid::orient::Update`).

@group(0) @binding(2) var<uniform> dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> turn_sum: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> before: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> id: array<u32>;
@group(0) @binding(6) var<storage, read> count: array<u32>;
@group(0) @binding(7) var<storage, read_write> orientation: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> spin: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let member = id[i];
    var n = 0u;
    if (member < arrayLength(&count)) {
        n = count[member];
    }
    if (n == 0u) {
        return;
    }
    // A melted particle, in no live cluster, stops turning.
    let s = turn_sum[i];
    var live = s.w > 0.0;
    if (solid.solver.z == 0u) {
        live = dot(s, s) > 0.0;
    }
    if (!live) {
        spin[i] = vec4<f32>(0.0);
        return;
    }
    var blended: vec4<f32>;
    if (solid.solver.z == 0u) {
        blended = normalize(s);
    } else {
        blended = normalize(quat_mul(quat_exp(s.xyz / s.w), before[i]));
    }
    spin[i] = vec4<f32>(quat_spin(blended, before[i], dt.x), 0.0);
    orientation[i] = blended;
}
