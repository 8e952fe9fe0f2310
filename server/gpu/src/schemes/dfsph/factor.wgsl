// DFSPH's factor (floe-engine `schemes::dfsph::cpu::Factor`): with
// `s = m_i sum_j grad W_ij + c sum_b psi_b grad W_ib`,
// `alpha = 1 / (|s|^2 + m_i^2 sum_j (m_i / m_j) |grad W_ij|^2)`, 0 without neighbours.

// z: the walls' factor c.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> alpha: array<f32>;

// The walk's hooks (walk.wgsl): the sums over i's neighbours and what they need of i.
var<private> factor_mat: vec4<f32>;
var<private> factor_fluid: vec3<f32>;
var<private> factor_sq: f32;
var<private> factor_wall: vec3<f32>;

fn walk_begin(i: u32) {
    factor_mat = params.materials[material_of(pos[i])];
    factor_fluid = vec3<f32>(0.0);
    factor_sq = 0.0;
    factor_wall = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_i = factor_mat.y;
    let g = kernel_grad(x_ij, r2);
    factor_fluid += g * m_i;
    factor_sq += dot(g, g) * (m_i / params.materials[material_of(pos[j])].y);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    factor_wall += kernel_grad(x_ib, r2) * (walls[b].w * factor_mat.w);
}

fn walk_end(i: u32) {
    let m_i = factor_mat.y;
    let s = factor_fluid + factor_wall * dfsph.z;
    let d = dot(s, s) + m_i * m_i * factor_sq;
    alpha[i] = select(0.0, 1.0 / d, d > 0.0);
}
