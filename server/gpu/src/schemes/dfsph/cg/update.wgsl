// A CG solve's step along its direction (floe-engine
// `schemes::dfsph::cg_cpu::Update`): a = RZ / PAP, kappa += a p, v -= dt a G p,
// r -= a A p.

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(2) var<storage, read> scalars: array<f32>;
@group(0) @binding(3) var<storage, read> dir: array<f32>;
@group(0) @binding(4) var<storage, read> gp: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> ap: array<f32>;
@group(0) @binding(6) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> kappa: array<f32>;
@group(0) @binding(8) var<storage, read_write> res: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let a = ratio(scalars[0], scalars[1]);
    kappa[i] += a * dir[i];
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz - gp[i].xyz * (step_dt.x * a), v.w);
    res[i] -= a * ap[i];
}
