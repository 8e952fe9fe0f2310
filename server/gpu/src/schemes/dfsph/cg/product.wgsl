// A p = D G p (floe-engine `schemes::dfsph::cg_cpu::Product`): the compression
// rate of the accelerations `gp`,
// `m_i sum_j (gp_i - gp_j) . grad W_ij + c sum_b psi_b gp_i . grad W_ib`, 0 for a
// held particle, and the term p_i Ap_i of p.Ap.

// z: the walls' factor c.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> gp: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> dir: array<f32>;
@group(0) @binding(7) var<storage, read> held: array<f32>;
@group(0) @binding(8) var<storage, read_write> ap: array<f32>;
@group(0) @binding(9) var<storage, read_write> dots: array<f32>;

// The walk's hooks (walk.wgsl).
var<private> product_gp_i: vec3<f32>;
var<private> product_mat: vec4<f32>;
var<private> product_fluid: f32;
var<private> product_wall: f32;

fn walk_begin(i: u32) {
    product_gp_i = gp[i].xyz;
    product_mat = params.materials[material_of(pos[i])];
    product_fluid = 0.0;
    product_wall = 0.0;
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    product_fluid += dot(product_gp_i - gp[j].xyz, kernel_grad(x_ij, r2));
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    product_wall += (walls[b].w * product_mat.w) * dot(product_gp_i, kernel_grad(x_ib, r2));
}

fn walk_end(i: u32) {
    let a = select(product_mat.y * product_fluid + dfsph.z * product_wall, 0.0, held[i] != 0.0);
    ap[i] = a;
    dots[i] = dir[i] * a;
}
