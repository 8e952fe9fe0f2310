// Density by summation over fluid and wall neighbours, then `p / rho^2`
// (floe-engine `cpu::passes::density`; Akinci et al. 2012, eq. 6):
// `rho_i = m sum_j W_ij + sum_b psi_b W_ib`.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> cell_start: array<u32>;
// Wall particles: xyz position (m), w pseudo-mass psi (kg).
@group(0) @binding(3) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> wall_start: array<u32>;
// Per particle: x density (kg/m^3), y p / rho^2.
@group(0) @binding(5) var<storage, read_write> dens: array<vec2<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    var sum = 0.0;
    let b = block_of(xi, params.grid_origin, params.inv_cell, params.grid_dims);
    for (var k = 0u; k < 9u; k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = cell_start[run.x]; j < cell_start[run.y]; j++) {
            let d = xi - pos[j].xyz;
            let r2 = dot(d, d);
            if (r2 < params.h2) {
                sum += kernel_w(r2);
            }
        }
    }
    var wall = 0.0;
    if (params.n_walls > 0u) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < 9u; k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = wall_start[run.x]; j < wall_start[run.y]; j++) {
                let w = walls[j];
                let d = xi - w.xyz;
                let r2 = dot(d, d);
                if (r2 < params.h2) {
                    wall += w.w * kernel_w(r2);
                }
            }
        }
    }
    let r = params.mass * sum + wall;
    dens[i] = vec2<f32>(r, pressure(r) / (r * r));
}
