// A CG solve's next direction p = alpha r + (RZ_NEW / RZ) p (floe-engine
// `schemes::dfsph::cg_cpu::Direction`).

// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(1) var<storage, read> scalars: array<f32>;
@group(0) @binding(2) var<storage, read> alpha: array<f32>;
@group(0) @binding(3) var<storage, read> res: array<f32>;
@group(0) @binding(4) var<storage, read_write> dir: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    dir[i] = alpha[i] * res[i] + ratio(scalars[2], scalars[0]) * dir[i];
}
