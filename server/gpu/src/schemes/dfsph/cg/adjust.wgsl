// A CG solve's adjusted start (floe-engine `schemes::dfsph::cg_cpu::Adjust`): with
// no particle held the residual's mean removed, with some the density solve
// started from max(rho, rho0); then the first direction p = alpha r.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(2) var<storage, read> scalars: array<f32>;
@group(0) @binding(3) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho: array<f32>;
@group(0) @binding(5) var<storage, read> alpha: array<f32>;
@group(0) @binding(6) var<storage, read> held: array<f32>;
@group(0) @binding(7) var<storage, read_write> res: array<f32>;
@group(0) @binding(8) var<storage, read_write> dir: array<f32>;

fn adjust(i: u32, density: bool) {
    var r = res[i];
    if (scalars[3] == 0.0) {
        r -= scalars[4] / f32(params.n);
    } else if (density && held[i] == 0.0) {
        let dt = step_dt.x;
        r += max(params.materials[material_of(pos[i])].x - rho[i], 0.0) / (dt * dt);
    }
    res[i] = r;
    dir[i] = alpha[i] * r;
}

@compute @workgroup_size(WG)
fn density(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        adjust(i, true);
    }
}

@compute @workgroup_size(WG)
fn divergence(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        adjust(i, false);
    }
}
