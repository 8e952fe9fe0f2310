// T += dt dT/dt with Kahan's compensation (floe-engine `modules::heat::passes`),
// dt the stage's.

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
    let s = compensated_add(temperature[i], temperature_carry[i], dt.x * heat_rate[i], dt.w);
    temperature[i] = s.x;
    temperature_carry[i] = s.y;
}
