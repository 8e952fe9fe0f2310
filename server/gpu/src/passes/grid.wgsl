// Counting sort of particles by grid cell (floe-engine `Grid::sort`), in four
// kernels around the prefix sum of the per-cell counts:
// 1. `count`: each particle's cell, and its rank among the cell's particles
//    (an atomic counter, so ranks come in arbitrary order);
// 2. (prefix sum of `counts` into run starts, see scan.wgsl);
// 3. `scatter`: `order[start[cell] + rank] = i`;
// 4. `settle`: one thread per cell sorts its run of `order` by old index,
//    which makes the sort stable and deterministic like the CPU's.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> cell_rank: array<vec2<u32>>;
@group(0) @binding(3) var<storage, read_write> counts: array<atomic<u32>>;
@group(0) @binding(4) var<storage, read_write> order: array<u32>;

@compute @workgroup_size(WG)
fn count(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let c = cell_index(cell_coords(pos[i].xyz, params.grid_origin, params.grid_inv_cell, params.grid_dims), params.grid_dims);
    cell_rank[i] = vec2<u32>(c, atomicAdd(&counts[c], 1u));
}

@compute @workgroup_size(WG)
fn scatter(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let cr = cell_rank[i];
    order[atomicLoad(&counts[cr.x]) + cr.y] = i;
}

@compute @workgroup_size(WG)
fn settle(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let c = thread_index(gid, groups);
    if (c >= params.cell_count) {
        return;
    }
    let start = atomicLoad(&counts[c]);
    let end = atomicLoad(&counts[c + 1u]);
    for (var a = start + 1u; a < end; a++) {
        let key = order[a];
        var b = a;
        while (b > start && order[b - 1u] > key) {
            order[b] = order[b - 1u];
            b--;
        }
        order[b] = key;
    }
}
