// The neighbour walk of a pair pass (floe-engine's pair loops over the step's
// neighbour lists, in the same order): one thread per particle i visits every
// fluid particle j within the kernel support and then, with walk_walls.wgsl,
// every wall particle b (walk_fluid.wgsl: passes that take no part of the walls),
// and hands each pair to the kernel's hooks:
//
//   walk_begin(i)                 before the first pair
//   walk_pair(i, j, x_ij, r2)     each fluid neighbour (x_ij = x_i - x_j, r2 > 0)
//   walk_walls() -> bool          whether to visit the walls (a kernel built with
//                                 `walls_if;` names it; every other kernel visits them)
//   walk_wall(i, b, x_ib, r2)     each wall neighbour (walk_walls.wgsl)
//   walk_end(i)                   after the last pair: write the results
//
// A kernel is these files, the pass's terms and the hooks, which keep their sums
// in private variables. Passes of one stage that walk the same neighbours share one
// walk when a device allows their bindings together ([`crate::pass::Fused`]): their
// hooks are called one after the other, and the walk, which costs more than most
// terms, is paid once.

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
    walk_wall_neighbours(i, xi);
    walk_end(i);
}
