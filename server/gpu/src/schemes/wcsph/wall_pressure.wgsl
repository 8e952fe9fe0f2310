// Pressure of each wall particle extrapolated from the fluid around it
// (floe-engine `schemes::wcsph::cpu::WallPressure`; Adami, Hu & Adams 2012,
// eq. 27): `p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf`.

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> starts: array<u32>;
@group(0) @binding(3) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> pterm: array<f32>;
@group(0) @binding(6) var<storage, read_write> wall_p: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let bi = thread_index(gid, groups);
    if (bi >= params.n_walls) {
        return;
    }
    let xb = walls[bi].xyz;
    var sum_w = 0.0;
    var sum_p = 0.0;
    var sum_rx = vec3<f32>(0.0);
    let b = block_of(xb, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_bj = separation(xb, pos[j].xyz);
            let r2 = dot(x_bj, x_bj);
            if (r2 < params.h2) {
                let w = kernel_w(r2);
                let r = rho[j];
                sum_w += w;
                sum_p += pterm[j] * r * r * w;
                sum_rx += x_bj * (r * w);
            }
        }
    }
    var p = 0.0;
    if (sum_w > 0.0) {
        p = max((sum_p + dot(params.gravity, sum_rx)) / sum_w, 0.0);
    }
    wall_p[bi] = p;
}
