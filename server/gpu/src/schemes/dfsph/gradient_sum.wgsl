// The walk's hooks that sum the pressure acceleration of a stiffness field `s`
// (floe-engine `schemes::dfsph::cpu::Sums::gradient`):
// `sum_j (m_i s_i + m_j^2 s_j / m_i) grad W_ij + c s_i sum_b psi_b grad W_ib`, which
// `gradient_sum(i)` returns in `walk_end`. The including kernel binds `dfsph` (z: the
// walls' factor c), `pos`, `walls` and `stiffness` (s), and writes `walk_end`.

var<private> gradient_mat: vec4<f32>;
var<private> gradient_own: f32;
var<private> gradient_a: vec3<f32>;
var<private> gradient_wall: vec3<f32>;

fn walk_begin(i: u32) {
    gradient_mat = params.materials[material_of(pos[i])];
    gradient_own = gradient_mat.y * stiffness[i];
    gradient_a = vec3<f32>(0.0);
    gradient_wall = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])].y;
    gradient_a += kernel_grad(x_ij, r2) * (gradient_own + m_j * m_j / gradient_mat.y * stiffness[j]);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    gradient_wall += kernel_grad(x_ib, r2) * (walls[b].w * gradient_mat.w);
}

fn gradient_sum(i: u32) -> vec3<f32> {
    return gradient_a + gradient_wall * (dfsph.z * stiffness[i]);
}
