// δ-SPH's density rate (floe-engine `schemes::wcsph::continuity`): the continuity
// equation `m_i sum_j v_ij . grad W_ij + sum_b psi_b v_i . grad W_ib` plus the
// diffusion `2 delta h c sum_j V_j (rho_i - rho_j - rho^H_ij) (x_ij . grad W_ij) /
// (r^2 + eta^2)` between particles of one material (Molteni & Colagrossi 2009;
// the hydrostatic part `rho^H_ij = rho0 g . x_ij / c^2` of Fourtakas et al. 2019).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> drho: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let rho_i = rho[i];
    let ma = material_of(pos[i]);
    let mat = params.materials[ma];
    let hydro = wcsph.hydrostatic[ma].xyz;
    var div = 0.0;
    var diffusion = 0.0;
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
            let dw = kernel_dw_dr(r);
            div += dot(vi - vel[j].xyz, x_ij) * (dw / r);
            let mb = material_of(pos[j]);
            if (mb == ma) {
                let v_j = params.materials[mb].y / rho[j];
                diffusion += v_j * (rho_i - rho[j] - dot(hydro, x_ij)) * (r * dw) / (r2 + wcsph.delta.y);
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
                let x_ib = separation(xi, w.xyz);
                let r2 = dot(x_ib, x_ib);
                if (r2 >= params.h2 || r2 == 0.0) {
                    continue;
                }
                let r = sqrt(r2);
                wall += w.w * mat.w * dot(vi, x_ib) * (kernel_dw_dr(r) / r);
            }
        }
    }
    drho[i] = mat.y * div + wall + wcsph.delta.x * diffusion;
}
