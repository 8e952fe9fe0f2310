// Particles of colour `sweep` (id % colours) below the floor are lifted onto it.

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> id: array<u32>;
@group(0) @binding(4) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n || id[i] % tracer.colours != sweep.x) {
        return;
    }
    pos[i].y = max(pos[i].y, tracer.floor);
}
