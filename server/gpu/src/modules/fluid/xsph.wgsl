// XSPH (Monaghan 1989, eq. 2.6; floe-engine `modules::fluid::xsph`): `main`
// sums `dv_i = eps_i sum_j 2 m_j / (rho_i + rho_j) (v_j - v_i) W_ij`; `kick`
// adds it to the velocity after the kick that follows an evaluation.

struct Fluid {
    material: array<vec4<f32>, 16>,
    pair: array<vec4<f32>, 256>,
}

@group(0) @binding(1) var<uniform> fluid: Fluid;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> starts: array<u32>;
@group(0) @binding(6) var<storage, read_write> xsph: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let xi = pos[i].xyz;
    let vi = vel[i].xyz;
    let rho_i = rho[i];
    var dv = vec3<f32>(0.0);
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2 || r2 == 0.0) {
                continue;
            }
            let m = params.materials[material_of(pos[j])].y;
            dv -= (vi - vel[j].xyz) * (2.0 * m / (rho_i + rho[j]) * kernel_w(r2));
        }
    }
    xsph[i] = vec4<f32>(dv * fluid.material[material_of(pos[i])].w, 0.0);
}

@compute @workgroup_size(WG)
fn kick(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    vel[i] = vec4<f32>(vel[i].xyz + xsph[i].xyz, 0.0);
}
