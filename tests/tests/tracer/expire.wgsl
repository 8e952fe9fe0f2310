// Marks the particles older than the lifetime for removal.

@group(0) @binding(2) var<storage, read> age: array<f32>;
@group(0) @binding(3) var<storage, read_write> remove: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    if (age[i] > tracer.lifetime) {
        remove[i] += 1.0;
    }
}
