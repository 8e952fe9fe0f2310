// At the first step, whether the scene is closed (floe-engine
// `schemes::dfsph::cg_cpu::Closed`): undecided (0), it becomes closed (1) if no
// particle is held, else open (2); decided, it stays. One thread.

// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(1) var<storage, read> scalars: array<f32>;
@group(0) @binding(2) var<storage, read_write> closed: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    if (thread_index(gid, groups) != 0u) {
        return;
    }
    if (closed[0] == 0.0) {
        closed[0] = select(2.0, 1.0, scalars[3] == 0.0);
    }
}
