// Gravity, pressure and viscous accelerations, and the XSPH correction
// (floe-engine `cpu::passes::forces`): symmetric pressure (Monaghan 1992,
// eq. 3.3) with wall particles weighted by Akinci's pseudo-mass and given
// Adami's extrapolated pressure; viscosity per the scene's model; XSPH
// (Monaghan 1989, eq. 2.6) `dv_i = eps sum_j 2 m / (rho_i + rho_j) (v_j - v_i) W_ij`.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> dens: array<vec2<f32>>;
@group(0) @binding(4) var<storage, read> cell_start: array<u32>;
@group(0) @binding(5) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> wall_start: array<u32>;
@group(0) @binding(7) var<storage, read> wall_p: array<f32>;
// Accelerations (m/s^2) in [0, n), XSPH corrections (m/s) in [n, 2n).
@group(0) @binding(8) var<storage, read_write> acc: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let di = dens[i];
    let m = params.mass;
    var a = params.gravity;
    var dv = vec3<f32>(0.0);
    let b = block_of(xi, params.grid_origin, params.inv_cell, params.grid_dims);
    for (var k = 0u; k < 9u; k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = cell_start[run.x]; j < cell_start[run.y]; j++) {
            let x_ij = xi - pos[j].xyz;
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let r = sqrt(r2);
            let grad = x_ij * (kernel_dw_dr(r) / r);
            let dj = dens[j];
            a -= grad * (m * (di.y + dj.y));
            let v_ij = vi - vel[j].xyz;
            a += viscosity(x_ij, r, v_ij, m, di.x, dj.x, grad);
            if (params.xsph > 0.0) {
                dv -= v_ij * (2.0 * m / (di.x + dj.x) * kernel_w(r2));
            }
        }
    }
    if (params.n_walls > 0u) {
        let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
        for (var k = 0u; k < 9u; k++) {
            let run = run_cells(bw, k, params.wall_dims);
            for (var j = wall_start[run.x]; j < wall_start[run.y]; j++) {
                let w = walls[j];
                let x_ib = xi - w.xyz;
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                let r = sqrt(r2);
                let grad = x_ib * (kernel_dw_dr(r) / r);
                a -= grad * (w.w * (di.y + wall_p[j] * params.inv_rho0_2));
                a += viscosity(x_ib, r, vi, w.w, di.x, params.rho0, grad);
            }
        }
    }
    acc[i] = vec4<f32>(a, 0.0);
    // Only scenes with XSPH compute and store the correction (the kick reads it
    // only then).
    if (params.xsph > 0.0) {
        acc[params.n + i] = vec4<f32>(dv * params.xsph, 0.0);
    }
}
