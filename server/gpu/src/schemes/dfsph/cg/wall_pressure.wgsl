// The walls' hydrostatic pressure as a kick before the constant-density solve
// (floe-engine `schemes::dfsph::cg_cpu::WallPressure`):
// v_i -= dt sum_b psi_b P'_b grad W_ib with P'_b = g . (x_b - x_i) / rho0_i, at a free
// surface (some particle held) no less than -(kappa_i + kappa_v_i).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(2) var<storage, read> scalars: array<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> kappa: array<f32>;
@group(0) @binding(5) var<storage, read> kappa_v: array<f32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> vel: array<vec4<f32>>;

var<private> least: f32;
// The fluid's material: x its rest density, w its rest density over material 0's
// (the walls' psi_b, kept for material 0, scaled to this fluid's).
var<private> mat: vec4<f32>;
var<private> a: vec3<f32>;

fn walk_begin(i: u32) {
    mat = params.materials[material_of(pos[i])];
    // -3.4e38: no least pressure in a closed domain.
    least = select(-3.4e38, -(kappa[i] + kappa_v[i]), scalars[3] > 0.0);
    a = vec3<f32>(0.0);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    a += kernel_grad(x_ib, r2) * ((walls[b].w * mat.w) * max(-dot(params.gravity, x_ib) / mat.x, least));
}

fn walk_end(i: u32) {
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - a * step_dt.x, v.w);
}
