// The pressure force of one DFSPH iteration's increments `dP` as a kick, the
// increments added to the stiffness (floe-engine `schemes::dfsph::cpu::Kick`):
// `v_i -= dt (sum_j (m_i dP_i + m_j^2 dP_j / m_i) grad W_ij + dP_i sum_b psi_b grad W_ib)`.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> increment: array<f32>;
@group(0) @binding(6) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> kappa: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let dp_i = increment[i];
    kappa[i] += dp_i;
    let xi = pos[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    let m_i = mat.y;
    let own = m_i * dp_i;
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
            let m_j = params.materials[material_of(pos[j])].y;
            a += x_ij * (kernel_dw_dr(r) / r) * (own + m_j * m_j / m_i * increment[j]);
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
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - (a + wall * dp_i) * step_dt.x, v.w);
}
