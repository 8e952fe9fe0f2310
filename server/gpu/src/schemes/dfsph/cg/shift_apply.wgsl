// The particles moved by their shifts (floe-engine
// `schemes::dfsph::cg_cpu::ShiftApply`), back through a periodic face.

@group(0) @binding(1) var<storage, read> shift: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    // w keeps the particle's material.
    pos[i] = vec4<f32>(wrap_periodic(pos[i].xyz + shift[i].xyz), pos[i].w);
}
