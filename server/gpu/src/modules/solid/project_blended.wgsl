// The projection where the bodies melt: each particle's share of its solid
// update is alpha (1 - beta).

@group(0) @binding(7) var<storage, read> liquid_fraction: array<f32>;

@compute @workgroup_size(WG)
fn blended(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        project(i, solid.settings.x * (1.0 - liquid_fraction[i]));
    }
}
