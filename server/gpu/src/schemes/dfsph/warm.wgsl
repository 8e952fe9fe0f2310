// A DFSPH solve's warm start (floe-engine `schemes::dfsph::cpu::Warm`):
// `increment = WARM_START kappa`, `kappa = 0`; the kick that follows adds it back.

// x: the warm start fraction, y: the neighbours a particle needs in the
// divergence-free solve.
@group(0) @binding(1) var<uniform> dfsph: vec4<f32>;
@group(0) @binding(2) var<storage, read_write> kappa: array<f32>;
@group(0) @binding(3) var<storage, read_write> increment: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    increment[i] = dfsph.x * kappa[i];
    kappa[i] = 0.0;
}
