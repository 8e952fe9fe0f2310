// δ-SPH's density rate (floe-engine `schemes::wcsph::continuity`): the continuity
// equation `m_i sum_j v_ij . grad W_ij + sum_b psi_b v_i . grad W_ib` plus the
// diffusion `2 delta h c_a sum_j V_j (rho_i - rho_j - rho^H_ij) (x_ij . grad W_ij) /
// (r^2 + eta^2)` between particles of one material, c_a its own speed of sound
// (Molteni & Colagrossi 2009; the hydrostatic part `rho^H_ij = rho0 g . x_ij / c^2`
// of Fourtakas et al. 2019).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> drho: array<f32>;

// The walk's hooks (walk.wgsl): the sums over i's neighbours and what they need of i.
var<private> continuity_vi: vec3<f32>;
var<private> continuity_rho_i: f32;
var<private> continuity_ma: u32;
var<private> continuity_hydro: vec3<f32>;
var<private> continuity_coefficient: f32;
var<private> continuity_div: f32;
var<private> continuity_diffusion: f32;
var<private> continuity_wall: f32;

fn walk_begin(i: u32) {
    continuity_vi = vel[i].xyz;
    continuity_rho_i = rho[i];
    continuity_ma = material_of(pos[i]);
    let delta = wcsph.delta_material[continuity_ma];
    continuity_hydro = delta.xyz;
    continuity_coefficient = delta.w;
    continuity_div = 0.0;
    continuity_diffusion = 0.0;
    continuity_wall = 0.0;
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    let dw = kernel_dw_dr(r);
    continuity_div += dot(continuity_vi - vel[j].xyz, x_ij) * (dw / r);
    let mb = material_of(pos[j]);
    if (mb == continuity_ma) {
        let v_j = params.materials[mb].y / rho[j];
        let jump = continuity_rho_i - rho[j] - dot(continuity_hydro, x_ij);
        continuity_diffusion += v_j * jump * (r * dw) / (r2 + wcsph.delta.x);
    }
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    let psi = walls[b].w * params.materials[continuity_ma].w;
    continuity_wall += psi * dot(continuity_vi, x_ib) * (kernel_dw_dr(r) / r);
}

fn walk_end(i: u32) {
    let m_i = params.materials[continuity_ma].y;
    drho[i] = m_i * continuity_div + continuity_wall + continuity_coefficient * continuity_diffusion;
}
