// The transport velocity's push (floe-engine `schemes::wcsph::transport`; Adami, Hu
// & Adams 2013, eq. 13): the acceleration the background pressure p_b gives each
// particle, `-p_b sum_j (m_i / rho_i^2 + m_j (m_j / m_i) / rho_j^2) grad W_ij`, and
// walls with Akinci's pseudo-mass, `-p_b sum_b psi_b (1/rho_i^2 + 1/rho0^2) grad W_ib`.

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read_write> a_transport: array<vec4<f32>>;

fn inv2(r: f32) -> f32 {
    return 1.0 / (r * r);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let ma = material_of(pos[i]);
    let mat = params.materials[ma];
    let m_i = mat.y;
    let own = m_i * inv2(rho[i]);
    var sum = vec3<f32>(0.0);
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
            sum += x_ij * (kernel_dw_dr(r) / r * (own + m_j * (m_j / m_i) * inv2(rho[j])));
        }
    }
    if (params.n_walls > 0u) {
        let wall = inv2(rho[i]) + mat.z;
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
                sum += x_ib * (kernel_dw_dr(r) / r * (w.w * mat.w * wall));
            }
        }
    }
    a_transport[i] = vec4<f32>(sum * -wcsph.transport.x, 0.0);
}
