// Density by summation over particle and wall neighbours (floe-engine
// `cpu::core::Density`; Akinci et al. 2012, eq. 6; several materials after
// Solenthaler & Pajarola 2008, eq. 4): `rho_i = m_i sum_j W_ij + sum_b psi_b W_ib`,
// the wall pseudo-mass scaled to particle i's material.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
// Run starts of the particle grid, then of the wall grid (from params.wall_start).
@group(0) @binding(2) var<storage, read> starts: array<u32>;
// Wall particles: xyz position (m), w pseudo-mass psi (kg) for material 0.
@group(0) @binding(3) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> rho: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    var sum = 0.0;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let d = separation(xi, pos[j].xyz);
            let r2 = dot(d, d);
            if (r2 < params.h2) {
                sum += kernel_w(r2);
            }
        }
    }
    var wall = 0.0;
    if (params.n_walls > 0u) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < block_runs(bw); k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = starts[params.wall_start + run.x]; j < starts[params.wall_start + run.y]; j++) {
                let w = walls[j];
                let d = separation(xi, w.xyz);
                let r2 = dot(d, d);
                if (r2 < params.h2) {
                    wall += w.w * mat.w * kernel_w(r2);
                }
            }
        }
    }
    rho[i] = mat.y * sum + wall;
}
