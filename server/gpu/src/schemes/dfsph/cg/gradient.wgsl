// G p (floe-engine `schemes::dfsph::cg_cpu::Gradient`):
// `sum_j (m_i p_i + m_j^2 p_j / m_i) grad W_ij + c p_i sum_b psi_b grad W_ib` (the sum:
// gradient_sum.wgsl).

// z: the walls' factor c.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
// The direction p.
@group(0) @binding(5) var<storage, read> stiffness: array<f32>;
@group(0) @binding(6) var<storage, read_write> gp: array<vec4<f32>>;

fn walk_end(i: u32) {
    gp[i] = vec4<f32>(gradient_sum(i), 0.0);
}
