// The walk's wall neighbours (walk.wgsl), where the kernel's `walk_walls()` asks.

fn walk_wall_neighbours(i: u32, xi: vec3<f32>) {
    if (params.n_walls == 0u || !walk_walls()) {
        return;
    }
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
