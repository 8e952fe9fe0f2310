// DFSPH's factor (floe-engine `schemes::dfsph::cpu::Factor`): with
// `s = m_i sum_j grad W_ij + sum_b psi_b grad W_ib`,
// `alpha = 1 / (|s|^2 + m_i^2 sum_j (m_i / m_j) |grad W_ij|^2)`, 0 without neighbours.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> starts: array<u32>;
@group(0) @binding(3) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> alpha: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    let m_i = mat.y;
    var fluid = vec3<f32>(0.0);
    var sq = 0.0;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let r = sqrt(r2);
            let g = x_ij * (kernel_dw_dr(r) / r);
            fluid += g * m_i;
            sq += dot(g, g) * (m_i / params.materials[material_of(pos[j])].y);
        }
    }
    var wall = vec3<f32>(0.0);
    if (params.n_walls > 0u) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = starts[params.wall_start + run.x]; j < starts[params.wall_start + run.y]; j++) {
                let w = walls[j];
                let x_ib = separation(xi, w.xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                let r = sqrt(r2);
                wall += x_ib * (kernel_dw_dr(r) / r) * (w.w * mat.w);
            }
        }
    }
    let s = fluid + wall;
    let d = dot(s, s) + m_i * m_i * sq;
    alpha[i] = select(0.0, 1.0 / d, d > 0.0);
}
