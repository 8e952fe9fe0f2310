// The damping where the bodies melt: each particle's share is the damping times
// 1 - beta.

@group(0) @binding(6) var<storage, read> liquid_fraction: array<f32>;

@compute @workgroup_size(WG)
fn blended(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        damp(i, solid.rigid.x * (1.0 - liquid_fraction[i]));
    }
}
