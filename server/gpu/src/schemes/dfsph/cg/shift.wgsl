// Each particle's shift in a closed scene (floe-engine
// `schemes::dfsph::cg_cpu::Shift`): `-D sum_j V_j (1 + R (W_ij / W(dx))^4) grad W_ij`
// over the fluid (V_j = m_j / rho0_j) and the walls (V_b = psi_b / rho0_i), with
// `D = min(shift h v_max dt, SHIFT_MOST h^2)`, at most `limit` long, from the
// positions the drift left.

// The pass runs with the step's largest displacement v_max dt (m) in x.
@group(0) @binding(1) var<uniform> dt: vec4<f32>;
// [0] x, y: held.wgsl's and start.wgsl's, z: shift h (m), w: SHIFT_MOST h^2 (m^2);
// [1] x: the limit (m), y: the anti-clustering weight R, z: W(dx).
@group(0) @binding(2) var<uniform> dfsph_cg: array<vec4<f32>, 2>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> starts: array<u32>;
@group(0) @binding(5) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> shift: array<vec4<f32>>;

var<private> shift_mat: vec4<f32>;
var<private> shift_sum: vec3<f32>;

// The rest volume's factor `1 + R (W / W(dx))^4`.
fn shift_weight(r2: f32) -> f32 {
    let f = kernel_w(r2) / dfsph_cg[1].z;
    return 1.0 + dfsph_cg[1].y * (f * f) * (f * f);
}

fn walk_begin(i: u32) {
    shift_mat = params.materials[material_of(pos[i])];
    shift_sum = vec3<f32>(0.0);
}

fn walk_pair(i: u32, j: u32, x_ij: vec3<f32>, r2: f32) {
    let m_j = params.materials[material_of(pos[j])];
    shift_sum += kernel_grad(x_ij, r2) * (m_j.y / m_j.x * shift_weight(r2));
}

fn walk_wall(i: u32, b: u32, x_ib: vec3<f32>, r2: f32) {
    // psi_b = walls[b].w * (rho0_i / rho0_0).
    shift_sum += kernel_grad(x_ib, r2) * (walls[b].w * shift_mat.w / shift_mat.x * shift_weight(r2));
}

fn walk_end(i: u32) {
    var d = shift_sum * -min(dfsph_cg[0].z * dt.x, dfsph_cg[0].w);
    let l = length(d);
    if (l > dfsph_cg[1].x) {
        d *= dfsph_cg[1].x / l;
    }
    shift[i] = vec4<f32>(d, 0.0);
}
