// q = turn(w dt) q, the orientation before kept (floe-engine `solid::orient::Predict`).

@group(0) @binding(2) var<uniform> dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> spin: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> before: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> orientation: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let q = orientation[i];
    before[i] = q;
    orientation[i] = normalize(quat_mul(quat_turn(spin[i].xyz, dt.x), q));
}
