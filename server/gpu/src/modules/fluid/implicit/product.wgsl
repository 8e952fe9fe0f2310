// Ap_i = d_i p_i - dt sum_j w_ij p_j and the term p_i . Ap_i (floe-engine
// `modules::fluid::implicit::Product`, term by term in the same order). The walls'
// mirror term is in d alone.

// x: the step's dt (s).
@group(0) @binding(2) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> mu: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> dir: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> diag: array<f32>;
@group(0) @binding(9) var<storage, read_write> ap: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> dots: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let mu_i = mu[i];
    let m_i = params.materials[material_of(pos[i])].y;
    let inv_rho = 1.0 / rho[i];
    var off = vec3<f32>(0.0);
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
            off += dir[j].xyz * pair_weight(m_i, m_j, mu_i + mu[j], inv_rho, rho[j], r2);
        }
    }
    let p = dir[i].xyz;
    let out = p * diag[i] - off * step_dt.x;
    ap[i] = vec4<f32>(out, 0.0);
    dots[i] = dot(p, out);
}
