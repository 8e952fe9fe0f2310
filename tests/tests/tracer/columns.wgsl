// Counts the particles above each cell of the columns' grid (one thread per
// cell, every particle; `column_of` in mod.rs, the same arithmetic).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> column_count: array<f32>;

fn cell(axis: u32, at: f32) -> i32 {
    let k = floor((at - tracer.origin[axis]) / tracer.size[axis] * f32(tracer.dims[axis]));
    if (k >= 0.0 && k < f32(tracer.dims[axis])) {
        return i32(k);
    }
    return -1;
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let c = thread_index(gid, groups);
    if (c >= tracer.dims.x * tracer.dims.z) {
        return;
    }
    var count = 0.0;
    for (var i = 0u; i < params.n; i++) {
        let x = cell(0u, pos[i].x);
        let z = cell(2u, pos[i].z);
        if (x >= 0 && z >= 0 && u32(x) + tracer.dims.x * u32(z) == c) {
            count += 1.0;
        }
    }
    column_count[c] = count;
}
