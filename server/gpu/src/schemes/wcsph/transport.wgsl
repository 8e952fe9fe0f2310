// The transport velocity's push (floe-engine `schemes::wcsph::transport`; Adami, Hu
// & Adams 2013, eq. 13): the acceleration the background pressure p_b gives each
// particle, `-p_b sum_j (m_i / rho_i^2 + m_j (m_j / m_i) / rho_j^2) grad W_ij`, and
// walls with Akinci's pseudo-mass, `-p_b sum_b psi_b (1/rho_i^2 + 1/rho0^2) grad W_ib`.

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> starts: array<u32>;
@group(0) @binding(4) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> rho: array<f32>;
@group(0) @binding(6) var<storage, read_write> a_transport: array<vec4<f32>>;

fn inv2(r: f32) -> f32 {
    return 1.0 / (r * r);
}

// The walk's hooks (walk.wgsl): the sum over i's neighbours and what it needs of i.
var<private> transport_mat: vec4<f32>;
var<private> transport_own: f32;
var<private> transport_wall: f32;
var<private> transport_sum: vec3<f32>;

fn walk_begin(i: u32) {
    transport_mat = params.materials[material_of(pos[i])];
    transport_own = transport_mat.y * inv2(rho[i]);
    transport_wall = inv2(rho[i]) + transport_mat.z;
    transport_sum = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    let m_i = transport_mat.y;
    let m_j = params.materials[material_of(pos[j])].y;
    transport_sum += x_ij * (kernel_dw_dr(r) / r * (transport_own + m_j * (m_j / m_i) * inv2(rho[j])));
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    let r = sqrt(r2);
    transport_sum += x_ib * (kernel_dw_dr(r) / r * (walls[b].w * transport_mat.w * transport_wall));
}

fn walk_end(i: u32) {
    a_transport[i] = vec4<f32>(transport_sum * -wcsph.transport.x, 0.0);
}
