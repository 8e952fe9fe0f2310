// G p (floe-engine `schemes::dfsph::cg_cpu::Gradient`):
// `sum_j (m_i p_i + m_j^2 p_j / m_i) grad W_ij + c p_i sum_b psi_b grad W_ib`.

// z: the walls' factor c.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> dir: array<f32>;
@group(0) @binding(6) var<storage, read_write> gp: array<vec4<f32>>;

// The walk's hooks (walk.wgsl).
var<private> gradient_mat: vec4<f32>;
var<private> gradient_own: f32;
var<private> gradient_a: vec3<f32>;
var<private> gradient_wall: vec3<f32>;

fn walk_begin(i: u32) {
    gradient_mat = params.materials[material_of(pos[i])];
    gradient_own = gradient_mat.y * dir[i];
    gradient_a = vec3<f32>(0.0);
    gradient_wall = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])].y;
    gradient_a += kernel_grad(x_ij, r2) * (gradient_own + m_j * m_j / gradient_mat.y * dir[j]);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    gradient_wall += kernel_grad(x_ib, r2) * (walls[b].w * gradient_mat.w);
}

fn walk_end(i: u32) {
    gp[i] = vec4<f32>(gradient_a + gradient_wall * (dfsph.z * dir[i]), 0.0);
}
