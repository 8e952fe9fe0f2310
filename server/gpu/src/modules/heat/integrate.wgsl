// T += dt dT/dt with Kahan's compensation (floe-engine `modules::heat::passes`,
// `compensated_add`, the same operations in the same order), dt the stage's.

// The stage's dt (s) in x; y, z, w are 0.
@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<storage, read_write> temperature: array<f32>;
@group(0) @binding(3) var<storage, read_write> temperature_carry: array<f32>;
@group(0) @binding(4) var<storage, read> heat_rate: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let t = temperature[i];
    let y = dt.x * heat_rate[i] - temperature_carry[i];
    // The sum as rounded, made opaque to the shader compiler (its bits XOR those of
    // dt.w, always 0): compilers that treat float arithmetic as exact otherwise
    // simplify (t + y) - t - y to 0, and the carry with it.
    let next = bitcast<f32>(bitcast<u32>(t + y) ^ bitcast<u32>(dt.w));
    temperature_carry[i] = (next - t) - y;
    temperature[i] = next;
}
