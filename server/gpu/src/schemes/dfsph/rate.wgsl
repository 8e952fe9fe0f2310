// The compression rate `Drho/Dt` of particle i (kg/(m^3 s)) in x (the walls'
// term times the factor `c` in `dfsph.z`: 1 for Akinci's walls, 2 mirrored), its
// neighbours (itself not counted) in y (floe-engine `schemes::dfsph::cpu::Sums`).
// The including kernel binds `dfsph`, `pos`, `vel`, `starts` and `walls`.
fn rate(i: u32) -> vec2<f32> {
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    var fluid = 0.0;
    var count = 0u;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2) {
                continue;
            }
            count += 1u;
            if (r2 == 0.0) {
                continue;
            }
            fluid += dot(vi - vel[j].xyz, kernel_grad(x_ij, r2));
        }
    }
    var wall = 0.0;
    if (params.n_walls > 0u) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = starts[params.wall_start + run.x]; j < starts[params.wall_start + run.y]; j++) {
                let w = walls[j];
                let x_ib = separation(xi, w.xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2) {
                    continue;
                }
                count += 1u;
                if (r2 == 0.0) {
                    continue;
                }
                wall += (w.w * mat.w) * dot(vi, kernel_grad(x_ib, r2));
            }
        }
    }
    return vec2<f32>(mat.y * fluid + dfsph.z * wall, f32(count - 1u));
}
