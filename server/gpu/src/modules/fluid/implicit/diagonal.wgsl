// The diagonal d_i = m_i + dt (sum_j w_ij + w_iw) and the starting residual
// r_i = dt (sum_j w_ij (v_j - v_i) - w_iw v_i) (floe-engine
// `modules::fluid::implicit::Diagonal`, term by term in the same order); w_iw is the
// no-slip walls' mirror term m_i 4 mu_i / rho_i^2 sum_b psi_b |F_ib|, times the
// walls' shear factor.

// x: the step's dt (s).
@group(0) @binding(2) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read> mu: array<f32>;
@group(0) @binding(7) var<storage, read> starts: array<u32>;
@group(0) @binding(8) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> diag: array<f32>;
@group(0) @binding(10) var<storage, read_write> res: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let mu_i = mu[i];
    let ma = material_of(pos[i]);
    let mat = params.materials[ma];
    let m_i = mat.y;
    let inv_rho = 1.0 / rho[i];
    let eps_h2 = 0.01 * 0.25 * params.support * params.support;
    var sum_w = 0.0;
    var force = vec3<f32>(0.0);
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let m_j = params.materials[material_of(pos[j])].y;
            let w = pair_weight(m_i, m_j, mu_i + mu[j], inv_rho, rho[j], r2);
            sum_w += w;
            force += (vel[j].xyz - vi) * w;
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
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                let r = sqrt(r2);
                wall += (w.w * mat.w) * (-r * kernel_dw_dr(r) / (r2 + eps_h2));
            }
        }
    }
    let w_wall = m_i * 4.0 * viscous_walls.x * mu_i * inv_rho * inv_rho * wall * viscous_walls.y;
    let dt = step_dt.x;
    diag[i] = m_i + dt * (sum_w + w_wall);
    res[i] = vec4<f32>((force - vi * w_wall) * dt, 0.0);
}
