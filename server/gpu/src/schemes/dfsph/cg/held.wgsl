// The particles a CG solve holds at P = 0 (floe-engine
// `schemes::dfsph::cg_cpu::Held`): 1 with fewer neighbours than `dfsph.y`, a summed
// density below `dfsph.w` of rest, or, below rest, a rest-volume gradient sum
// `|sum_j V_j grad W_ij + sum_b V_b grad W_ib|` of at least `dfsph_cg.x` (1/m: a
// neighbourhood cut by a free surface); else 0; 0 for every particle of a closed scene.

// y: the neighbours a particle needs, w: the fraction of the rest density below which
// a particle is held.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
// x: the gradient sum at which an under-dense particle is held (y: start.wgsl's).
@group(0) @binding(2) var<uniform> dfsph_cg: vec4<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> held: array<f32>;
// 1 in a closed scene (closed.wgsl).
@group(0) @binding(8) var<storage, read> closed: array<f32>;

var<private> held_mat: vec4<f32>;
var<private> held_count: u32;
var<private> held_fluid: vec3<f32>;
var<private> held_wall: vec3<f32>;

fn walk_begin(i: u32) {
    held_mat = params.materials[material_of(pos[i])];
    held_count = 0u;
    held_fluid = vec3<f32>(0.0);
    held_wall = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])];
    held_count += 1u;
    held_fluid += kernel_grad(x_ij, r2) * (m_j.y / m_j.x);
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    held_count += 1u;
    held_wall += kernel_grad(x_ib, r2) * walls[b].w;
}

fn walk_end(i: u32) {
    // psi_b = walls[b].w * (rho0_i / rho0_0), so V_b = psi_b / rho0_i.
    let s = held_fluid + held_wall * (held_mat.w / held_mat.x);
    let cut = dfsph_cg.x;
    let rest = held_mat.x;
    let surface = rho[i] < rest && dot(s, s) >= cut * cut;
    let free = f32(held_count) >= dfsph.y && rho[i] >= dfsph.w * rest && !surface;
    held[i] = select(1.0, 0.0, closed[0] == 1.0 || free);
}
