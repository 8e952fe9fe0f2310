// A DFSPH solve's error from the current velocities (floe-engine
// `schemes::dfsph::cpu::Error`): the compression rate
// `Drho/Dt = m_i sum_j (v_i - v_j) . grad W_ij + sum_b psi_b v_i . grad W_ib`, the
// compression `e` it predicts (clamped at zero), the increment `e alpha / dt^2`
// (`density`) or `e alpha / dt` (`divergence`, only for particles with a full
// neighbourhood) and the residual `e / rho0` (times dt for the divergence).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// x: the warm start fraction, y: the neighbours a particle needs in the
// divergence-free solve.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read> alpha: array<f32>;
@group(0) @binding(7) var<storage, read> starts: array<u32>;
@group(0) @binding(8) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> increment: array<f32>;
@group(0) @binding(10) var<storage, read_write> residual: array<f32>;

// The compression rate of particle i (kg/(m^3 s)) in x, its neighbours (itself
// not counted) in y.
fn rate(i: u32) -> vec2<f32> {
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let mat = params.materials[material_of(pos[i])];
    var fluid = 0.0;
    var count = 0u;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2) {
                continue;
            }
            count += 1u;
            if (r2 == 0.0) {
                continue;
            }
            fluid += dot(vi - vel[j].xyz, kernel_grad(x_ij, r2));
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
                if (r2 >= params.h2) {
                    continue;
                }
                count += 1u;
                if (r2 == 0.0) {
                    continue;
                }
                wall += (w.w * mat.w) * dot(vi, kernel_grad(x_ib, r2));
            }
        }
    }
    return vec2<f32>(mat.y * fluid + wall, f32(count - 1u));
}

@compute @workgroup_size(WG)
fn density(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let dt = step_dt.x;
    let rho0 = params.materials[material_of(pos[i])].x;
    let e = max(rho[i] + dt * rate(i).x - rho0, 0.0);
    increment[i] = e * alpha[i] / (dt * dt);
    residual[i] = e / rho0;
}

@compute @workgroup_size(WG)
fn divergence(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let dt = step_dt.x;
    let rho0 = params.materials[material_of(pos[i])].x;
    let r = rate(i);
    let e = select(0.0, max(r.x, 0.0), r.y >= dfsph.y);
    increment[i] = e * alpha[i] / dt;
    residual[i] = dt * e / rho0;
}
