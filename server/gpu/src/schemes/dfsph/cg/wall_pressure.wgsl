// The walls' hydrostatic pressure as a kick before the constant-density solve
// (floe-engine `schemes::dfsph::cg_cpu::WallPressure`):
// v_i -= dt sum_b psi_b P'_b grad W_ib with P'_b = g . (x_b - x_i) / rho0_i, at a free
// surface (some particle held) no less than -(kappa_i + kappa_v_i).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(2) var<storage, read> scalars: array<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> kappa: array<f32>;
@group(0) @binding(5) var<storage, read> kappa_v: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> vel: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n || params.n_walls == 0u) {
        return;
    }
    let xi = pos[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    // -3.4e38: no least pressure in a closed domain.
    let least = select(-3.4e38, -(kappa[i] + kappa_v[i]), scalars[3] > 0.0);
    var a = vec3<f32>(0.0);
    let bw = block_of(xi, params.wall_origin, params.wall_inv_cell, params.wall_dims);
    for (var k = 0u; k < block_runs(bw); k++) {
        let run = run_cells(bw, k, params.wall_dims);
        for (var b = starts[params.wall_start + run.x]; b < starts[params.wall_start + run.y]; b++) {
            let x_ib = separation(xi, walls[b].xyz);
            let r2 = dot(x_ib, x_ib);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            a += kernel_grad(x_ib, r2) * ((walls[b].w * mat.w) * max(-dot(params.gravity, x_ib) / mat.x, least));
        }
    }
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - a * step_dt.x, v.w);
}
