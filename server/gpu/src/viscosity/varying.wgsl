// The viscous force of the per-particle viscosities (floe-engine
// `viscosity`, term by term in the same order): a_i += sum_j m_j (mu_i + mu_j) / (rho_i rho_j) F_ij v_ij (Morris,
// Fox & Zhu 1997), F_ij = r dW/dr / (r^2 + 0.01 h^2); a wall particle mirrors the
// particle (velocity -v_i, viscosity mu_i, density rho_i), times the walls' shear
// factor (0 for slip walls); the sum times the lattice normalisation.

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> mu: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> acc: array<vec4<f32>>;

// The walk's hooks (walk.wgsl): the sum over i's neighbours and what it needs of i.
var<private> varying_a: vec3<f32>;
var<private> varying_vi: vec3<f32>;
var<private> varying_mu_i: f32;
var<private> varying_inv_rho: f32;
var<private> varying_eps_h2: f32;
var<private> varying_psi: f32;
var<private> varying_mirror: vec3<f32>;

fn walk_begin(i: u32) {
    varying_vi = vel[i].xyz;
    varying_mu_i = mu[i];
    varying_inv_rho = 1.0 / rho[i];
    varying_eps_h2 = 0.01 * 0.25 * params.support * params.support;
    varying_psi = params.materials[material_of(pos[i])].w;
    varying_mirror = varying_vi * (4.0 * viscous_walls.x * varying_mu_i * varying_inv_rho * varying_inv_rho);
    varying_a = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    let f = r * kernel_dw_dr(r) / (r2 + varying_eps_h2);
    let m = params.materials[material_of(pos[j])].y;
    varying_a += (varying_vi - vel[j].xyz) * (m * (varying_mu_i + mu[j]) * varying_inv_rho / rho[j] * f);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    varying_a += varying_mirror * ((walls[b].w * varying_psi) * (r * kernel_dw_dr(r) / (r2 + varying_eps_h2)));
}

fn walk_end(i: u32) {
    acc[i] = vec4<f32>(acc[i].xyz + varying_a * viscous_walls.y, 0.0);
}
