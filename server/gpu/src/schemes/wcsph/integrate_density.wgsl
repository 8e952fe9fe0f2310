// `rho += dt drho` (floe-engine `schemes::wcsph::continuity::Integrate`).

// x: the step's dt (s).
@group(0) @binding(1) var<uniform> step_dt: vec4<f32>;
@group(0) @binding(2) var<storage, read> drho: array<f32>;
@group(0) @binding(3) var<storage, read_write> rho: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    rho[i] += drho[i] * step_dt.x;
}
