// The viscous force of the per-particle viscosities (floe-engine
// `modules::fluid::varying`, term by term in the same order): a_i += sum_j m_j (mu_i + mu_j) / (rho_i rho_j) F_ij v_ij (Morris,
// Fox & Zhu 1997), F_ij = r dW/dr / (r^2 + 0.01 h^2); a wall particle mirrors the
// particle (velocity -v_i, viscosity mu_i, density rho_i), times the walls' shear
// factor (0 for slip walls); the sum times the lattice normalisation.

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> mu: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> acc: array<vec4<f32>>;

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
    let inv_rho = 1.0 / rho[i];
    let eps_h2 = 0.01 * 0.25 * params.support * params.support;
    var a = vec3<f32>(0.0);
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
            let f = r * kernel_dw_dr(r) / (r2 + eps_h2);
            let m = params.materials[material_of(pos[j])].y;
            a += (vi - vel[j].xyz) * (m * (mu_i + mu[j]) * inv_rho / rho[j] * f);
        }
    }
    if (params.n_walls > 0u) {
        let mat = params.materials[ma];
        let mirror = vi * (4.0 * viscous_walls.x * mu_i * inv_rho * inv_rho);
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
                a += mirror * ((w.w * mat.w) * (r * kernel_dw_dr(r) / (r2 + eps_h2)));
            }
        }
    }
    acc[i] = vec4<f32>(acc[i].xyz + a * viscous_walls.y, 0.0);
}
