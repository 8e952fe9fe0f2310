// The diagonal d_i = m_i + dt (sum_j w_ij + w_iw) and the starting residual
// r_i = dt (sum_j w_ij (v_j - v_i) - w_iw v_i) (floe-engine
// `viscosity::implicit::Diagonal`, term by term in the same order); w_iw is the
// no-slip walls' mirror term m_i 4 mu_i / rho_i^2 sum_b psi_b |F_ib|, times the
// walls' shear factor.

// x: the step's dt (s).
@group(0) @binding(2) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read> mu: array<f32>;
@group(0) @binding(7) var<storage, read> starts: array<u32>;
@group(0) @binding(8) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> diag: array<f32>;
@group(0) @binding(10) var<storage, read_write> res: array<vec4<f32>>;

// The walk's hooks (walk.wgsl): the sums over i's neighbours and what they need of i.
var<private> diagonal_vi: vec3<f32>;
var<private> diagonal_mu_i: f32;
var<private> diagonal_mat: vec4<f32>;
var<private> diagonal_inv_rho: f32;
var<private> diagonal_eps_h2: f32;
var<private> diagonal_sum_w: f32;
var<private> diagonal_force: vec3<f32>;
var<private> diagonal_wall: f32;

fn walk_begin(i: u32) {
    diagonal_vi = vel[i].xyz;
    diagonal_mu_i = mu[i];
    diagonal_mat = params.materials[material_of(pos[i])];
    diagonal_inv_rho = 1.0 / rho[i];
    diagonal_eps_h2 = 0.01 * 0.25 * params.support * params.support;
    diagonal_sum_w = 0.0;
    diagonal_force = vec3<f32>(0.0);
    diagonal_wall = 0.0;
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])].y;
    let w = pair_weight(diagonal_mat.y, m_j, diagonal_mu_i + mu[j], diagonal_inv_rho, rho[j], r2);
    diagonal_sum_w += w;
    diagonal_force += (vel[j].xyz - diagonal_vi) * w;
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    diagonal_wall += (walls[b].w * diagonal_mat.w) * (-r * kernel_dw_dr(r) / (r2 + diagonal_eps_h2));
}

fn walk_end(i: u32) {
    let m_i = diagonal_mat.y;
    let inv_rho = diagonal_inv_rho;
    let w_wall = m_i * 4.0 * viscous_walls.x * diagonal_mu_i * inv_rho * inv_rho * diagonal_wall * viscous_walls.y;
    let dt = step_dt.x;
    diag[i] = m_i + dt * (diagonal_sum_w + w_wall);
    res[i] = vec4<f32>((diagonal_force - diagonal_vi * w_wall) * dt, 0.0);
}
