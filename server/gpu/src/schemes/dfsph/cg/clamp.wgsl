// A CG solve's clamp (floe-engine `schemes::dfsph::cg_cpu::Clamp`): where a free
// surface exists (some particle held), the increment max(kappa, 0) - kappa that
// the solve's kick applies next; else 0.

// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(1) var<storage, read> scalars: array<f32>;
@group(0) @binding(2) var<storage, read> kappa: array<f32>;
@group(0) @binding(3) var<storage, read_write> increment: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    increment[i] = select(0.0, max(-kappa[i], 0.0), scalars[3] > 0.0);
}
