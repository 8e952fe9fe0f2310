// A DFSPH solve's error from the current velocities (floe-engine
// `schemes::dfsph::cpu::Error`): the compression rate
// `Drho/Dt = m_i sum_j (v_i - v_j) . grad W_ij + sum_b psi_b v_i . grad W_ib`, the
// compression `e` it predicts (clamped at zero), the increment `e alpha / dt^2`
// (`density`) or `e alpha / dt` (`divergence`, only for particles with a full
// neighbourhood) and the residual `e / rho0` (times dt for the divergence).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// x: the warm start fraction, y: the neighbours a particle needs in the
// divergence-free solve, z: the walls' factor.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read> alpha: array<f32>;
@group(0) @binding(7) var<storage, read> starts: array<u32>;
@group(0) @binding(8) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> increment: array<f32>;
@group(0) @binding(10) var<storage, read_write> residual: array<f32>;

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
