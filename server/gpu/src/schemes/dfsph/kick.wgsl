// The pressure force of one DFSPH iteration's increments `dP` as a kick, the
// increments added to the stiffness (floe-engine `schemes::dfsph::cpu::Kick`):
// `v_i -= dt (sum_j (m_i dP_i + m_j^2 dP_j / m_i) grad W_ij + c dP_i sum_b psi_b grad W_ib)`
// (the sum: gradient_sum.wgsl).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// z: the walls' factor c.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> starts: array<u32>;
@group(0) @binding(5) var<storage, read> walls: array<vec4<f32>>;
// The increments dP.
@group(0) @binding(6) var<storage, read> stiffness: array<f32>;
@group(0) @binding(7) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> kappa: array<f32>;

fn walk_end(i: u32) {
    kappa[i] += stiffness[i];
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - gradient_sum(i) * step_dt.x, v.w);
}
