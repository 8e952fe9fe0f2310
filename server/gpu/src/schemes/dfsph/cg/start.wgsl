// A CG solve's start (floe-engine `schemes::dfsph::cg_cpu::Start`): the residual
// `r = b` from the current velocities, `(rho + dt Drho/Dt - rho0) / dt^2`
// (`density`) or `(Drho/Dt) / dt` (`divergence`), 0 for a held particle. In a closed
// domain (no particle held) the density's deviation `rho - rho0` is its Shepard mean
// over the fluid neighbours plus `dfsph_cg.y` (floe-engine `cg::RAW_EXCESS`) of the
// particle's own difference from it.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// z: the walls' factor.
@group(0) @binding(2) var<uniform> dfsph: vec4<f32>;
// y: the share of a particle's own deviation in a closed domain.
@group(0) @binding(3) var<uniform> dfsph_cg: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(4) var<storage, read> scalars: array<f32>;
@group(0) @binding(5) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> rho: array<f32>;
@group(0) @binding(8) var<storage, read> starts: array<u32>;
@group(0) @binding(9) var<storage, read> walls: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> held: array<f32>;
@group(0) @binding(11) var<storage, read_write> res: array<f32>;

// The deviation `rho - rest` of particle i as a closed domain's density solve takes it.
fn filtered_excess(i: u32, rest: f32) -> f32 {
    let xi = pos[i].xyz;
    var sum = 0.0;
    var weight = 0.0;
    let b = block_of(xi, params.grid_origin, params.grid_inv_cell, params.grid_dims);
    for (var k = 0u; k < block_runs(b); k++) {
        let run = run_cells(b, k, params.grid_dims);
        for (var j = starts[run.x]; j < starts[run.y]; j++) {
            let x_ij = separation(xi, pos[j].xyz);
            let r2 = dot(x_ij, x_ij);
            if (r2 >= params.h2) {
                continue;
            }
            let w = kernel_w(r2);
            sum += w * (rho[j] - rest);
            weight += w;
        }
    }
    let mean = sum / weight;
    return mean + dfsph_cg.y * (rho[i] - rest - mean);
}

// Writes r, the density solve's if `density`.
fn start(i: u32, density: bool) {
    if (held[i] != 0.0) {
        res[i] = 0.0;
        return;
    }
    let dt = step_dt.x;
    let r = rate(i);
    let rest = params.materials[material_of(pos[i])].x;
    if (density && scalars[3] == 0.0) {
        res[i] = (filtered_excess(i, rest) + dt * r.x) / (dt * dt);
    } else if (density) {
        res[i] = (rho[i] + dt * r.x - rest) / (dt * dt);
    } else {
        res[i] = r.x / dt;
    }
}

@compute @workgroup_size(WG)
fn density(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        start(i, true);
    }
}

@compute @workgroup_size(WG)
fn divergence(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        start(i, false);
    }
}
