// XSPH (Monaghan 1989, eq. 2.6; floe-engine `modules::fluid::xsph`): the sum
// `dv_i = eps_i sum_j 2 m_j / (rho_i + rho_j) (v_j - v_i) W_ij` (xsph_kick.wgsl
// adds it to the velocity after the kick that follows an evaluation).

struct Fluid {
    material: array<vec4<f32>, 16>,
    pair: array<vec4<f32>, 256>,
}

@group(0) @binding(1) var<uniform> fluid: Fluid;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read_write> xsph: array<vec4<f32>>;

// The walk's hooks (walk.wgsl, fluid neighbours only) of `main`: the sum over i's
// neighbours and what it needs of i.
var<private> xsph_vi: vec3<f32>;
var<private> xsph_rho_i: f32;
var<private> xsph_dv: vec3<f32>;

fn walk_begin(i: u32) {
    xsph_vi = vel[i].xyz;
    xsph_rho_i = rho[i];
    xsph_dv = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m = params.materials[material_of(pos[j])].y;
    xsph_dv -= (xsph_vi - vel[j].xyz) * (2.0 * m / (xsph_rho_i + rho[j]) * kernel_w(r2));
}

fn walk_end(i: u32) {
    xsph[i] = vec4<f32>(xsph_dv * fluid.material[material_of(pos[i])].w, 0.0);
}
