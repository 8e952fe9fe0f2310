// A CG solve's warm start (floe-engine `schemes::dfsph::cg_cpu::Warm`):
// increment = w kappa, kappa = 0, with w 1 where a free surface exists (some
// particle held) and `dfsph.x` in a closed domain; 0 for a held particle, whose
// stiffness is zero.

// x: the warm start fraction in a closed domain.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
// The solves' scalars: r.z, p.Ap, the new r.z, held particles, the residual's sum.
@group(0) @binding(2) var<storage, read> scalars: array<f32>;
@group(0) @binding(3) var<storage, read_write> kappa: array<f32>;
@group(0) @binding(4) var<storage, read_write> increment: array<f32>;
// 1 where held at zero pressure, else 0.
@group(0) @binding(5) var<storage, read> held: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    increment[i] = select(dfsph.x, 1.0, scalars[3] > 0.0) * kappa[i] * (1.0 - held[i]);
    kappa[i] = 0.0;
}
