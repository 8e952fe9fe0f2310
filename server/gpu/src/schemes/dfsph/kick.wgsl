// The pressure force of one DFSPH iteration's increments `dP` as a kick, the
// increments added to the stiffness (floe-engine `schemes::dfsph::cpu::Kick`):
// `v_i -= dt (sum_j (m_i dP_i + m_j^2 dP_j / m_i) grad W_ij + c dP_i sum_b psi_b grad W_ib)`.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// z: the walls' factor c.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> starts: array<u32>;
@group(0) @binding(5) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> increment: array<f32>;
@group(0) @binding(7) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> kappa: array<f32>;

// The walk's hooks (walk.wgsl): the sums over i's neighbours and what they need of i.
var<private> kick_dp_i: f32;
var<private> kick_mat: vec4<f32>;
var<private> kick_own: f32;
var<private> kick_a: vec3<f32>;
var<private> kick_wall: vec3<f32>;

fn walk_begin(i: u32) {
    kick_dp_i = increment[i];
    kappa[i] += kick_dp_i;
    kick_mat = params.materials[material_of(pos[i])];
    kick_own = kick_mat.y * kick_dp_i;
    kick_a = vec3<f32>(0.0);
    kick_wall = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])].y;
    kick_a += kernel_grad(x_ij, r2) * (kick_own + m_j * m_j / kick_mat.y * increment[j]);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    kick_wall += kernel_grad(x_ib, r2) * (walls[b].w * kick_mat.w);
}

fn walk_end(i: u32) {
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - (kick_a + kick_wall * (dfsph.z * kick_dp_i)) * step_dt.x, v.w);
}
