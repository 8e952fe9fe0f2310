// Every probe gets the particles' mean age (one thread per probe).

@group(0) @binding(2) var<storage, read> age: array<f32>;
@group(0) @binding(3) var<storage, read_write> probe_age: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= tracer.probes) {
        return;
    }
    var sum = 0.0;
    for (var i = 0u; i < params.n; i++) {
        sum += age[i];
    }
    probe_age[k] = sum / f32(max(params.n, 1u));
}
