// Shear rate and viscosity (floe-engine `modules::snow::viscous`, term by term in
// the same order): L_i = 1/rho_i sum_j m_j (v_j - v_i) (x) grad W_ij, walls
// mirroring the particle's velocity; D = (L + L^T)/2; g = sqrt(2 D:D); mu(g),
// scaled by the heat module's temperature shift where a scene has it
// (shear_shifted.wgsl; shear_plain.wgsl otherwise).

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> mu: array<f32>;
@group(0) @binding(8) var<storage, read_write> shear_rate: array<f32>;

// The walk's hooks (walk.wgsl): the rows of L and what they need of i.
var<private> shear_lx: vec3<f32>;
var<private> shear_ly: vec3<f32>;
var<private> shear_lz: vec3<f32>;
var<private> shear_vi: vec3<f32>;
var<private> shear_ma: u32;
var<private> shear_inv_rho: f32;

fn walk_begin(i: u32) {
    shear_vi = vel[i].xyz;
    shear_ma = material_of(pos[i]);
    shear_inv_rho = 1.0 / rho[i];
    shear_lx = vec3<f32>(0.0);
    shear_ly = vec3<f32>(0.0);
    shear_lz = vec3<f32>(0.0);
}

fn shear_add(grad: vec3<f32>, dv: vec3<f32>) {
    shear_lx += grad * dv.x;
    shear_ly += grad * dv.y;
    shear_lz += grad * dv.z;
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let grad = kernel_grad(x_ij, r2);
    shear_add(grad, (vel[j].xyz - shear_vi) * (params.materials[material_of(pos[j])].y * shear_inv_rho));
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    let grad = kernel_grad(x_ib, r2);
    let psi = walls[b].w * params.materials[shear_ma].w;
    shear_add(grad, shear_vi * (-2.0 * snow.kind[shear_ma].z * psi * shear_inv_rho));
}

fn walk_end(i: u32) {
    let lx = shear_lx;
    let ly = shear_ly;
    let lz = shear_lz;
    let d = array<f32, 6>(lx.x, ly.y, lz.z, 0.5 * (lx.y + ly.x), 0.5 * (lx.z + lz.x), 0.5 * (ly.z + lz.y));
    let diag = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let off = d[3] * d[3] + d[4] * d[4] + d[5] * d[5];
    let g = sqrt(2.0 * (diag + 2.0 * off));
    shear_rate[i] = g;
    mu[i] = scaled(i, shear_ma, viscosity_of(shear_ma, g));
}
