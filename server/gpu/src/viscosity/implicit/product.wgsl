// Ap_i = d_i p_i - dt sum_j w_ij p_j and the term p_i . Ap_i (floe-engine
// `viscosity::implicit::Product`, term by term in the same order). The walls'
// mirror term is in d alone.

// x: the step's dt (s).
@group(0) @binding(2) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> mu: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> dir: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> diag: array<f32>;
@group(0) @binding(9) var<storage, read_write> ap: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> dots: array<f32>;

// The walk's hooks (walk.wgsl, fluid neighbours only): the sum over i's
// neighbours and what it needs of i.
var<private> product_mu_i: f32;
var<private> product_m_i: f32;
var<private> product_inv_rho: f32;
var<private> product_off: vec3<f32>;

fn walk_begin(i: u32) {
    product_mu_i = mu[i];
    product_m_i = params.materials[material_of(pos[i])].y;
    product_inv_rho = 1.0 / rho[i];
    product_off = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])].y;
    product_off += dir[j].xyz * pair_weight(product_m_i, m_j, product_mu_i + mu[j], product_inv_rho, rho[j], r2);
}

fn walk_end(i: u32) {
    let p = dir[i].xyz;
    let out = p * diag[i] - product_off * step_dt.x;
    ap[i] = vec4<f32>(out, 0.0);
    dots[i] = dot(p, out);
}
