// Particles older than the phase age change into the phase `aged`: the material
// index rides in the w of each position.

@group(0) @binding(2) var<storage, read> age: array<f32>;
@group(0) @binding(3) var<storage, read_write> x: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    if (age[i] > tracer.phase_age) {
        x[i].w = f32(tracer.aged);
    }
}
