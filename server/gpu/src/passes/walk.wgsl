// The neighbour walk of a pair pass (floe-engine's pair loops over the step's
// neighbour lists, in the same order): one thread per particle i visits every
// fluid particle j and, where `walk_walls()` says so, every wall particle b
// within the kernel support, and hands each pair to the kernel's hooks:
//
//   walk_begin(i)                 before the first pair
//   walk_pair(i, j, x_ij, r2)     each fluid neighbour (x_ij = x_i - x_j, r2 > 0)
//   walk_walls() -> bool          whether to visit the walls at all
//   walk_wall(i, b, x_ib, r2)     each wall neighbour
//   walk_end(i)                   after the last pair: write the results
//
// A kernel is this file, the passes' terms and a few lines naming the hooks. Passes
// of one stage that walk the same neighbours share one walk when a device allows
// their bindings together ([`crate::pass::Fused`]): their hooks are called one
// after the other, and the walk, which costs more than most terms, is paid once.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    walk_begin(i);
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            walk_pair(i, j, x_ij, r2);
        }
    }
    if (params.n_walls > 0u && walk_walls()) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var b = starts[params.wall_start + run.x]; b < starts[params.wall_start + run.y]; b++) {
                let x_ib = separation(xi, walls[b].xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                walk_wall(i, b, x_ib, r2);
            }
        }
    }
    walk_end(i);
}
