// Shear rate and viscosity (floe-engine `modules::snow::viscous`, term by term in
// the same order): L_i = 1/rho_i sum_j m_j (v_j - v_i) (x) grad W_ij, walls
// mirroring the particle's velocity; D = (L + L^T)/2; g = sqrt(2 D:D); mu(g),
// scaled by the heat module's temperature shift where a scene has it
// (shear_shifted.wgsl; shear_plain.wgsl otherwise).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> mu: array<f32>;
@group(0) @binding(8) var<storage, read_write> shear_rate: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let ma = material_of(pos[i]);
    let inv_rho = 1.0 / rho[i];
    // Rows of L.
    var lx = vec3<f32>(0.0);
    var ly = vec3<f32>(0.0);
    var lz = vec3<f32>(0.0);
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
            let grad = x_ij * (kernel_dw_dr(r) / r);
            let dv = (vel[j].xyz - vi) * (params.materials[material_of(pos[j])].y * inv_rho);
            lx += grad * dv.x;
            ly += grad * dv.y;
            lz += grad * dv.z;
        }
    }
    if (params.n_walls > 0u) {
        let mat = params.materials[ma];
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
                let grad = x_ib * (kernel_dw_dr(r) / r);
                let dv = vi * (-2.0 * snow.kind[ma].z * (w.w * mat.w) * inv_rho);
                lx += grad * dv.x;
                ly += grad * dv.y;
                lz += grad * dv.z;
            }
        }
    }
    let d = array<f32, 6>(lx.x, ly.y, lz.z, 0.5 * (lx.y + ly.x), 0.5 * (lx.z + lz.x), 0.5 * (ly.z + lz.y));
    let diag = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let off = d[3] * d[3] + d[4] * d[4] + d[5] * d[5];
    let g = sqrt(2.0 * (diag + 2.0 * off));
    shear_rate[i] = g;
    mu[i] = scaled(i, ma, viscosity_of(ma, g));
}
