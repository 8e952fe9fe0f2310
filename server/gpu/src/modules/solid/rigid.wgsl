// Per cluster: its rigid motion, the mean velocity of its live members and the
// angular velocity I^-1 L, the inertia regularised by a millionth of its trace
// (floe-engine `solid::cpu::Rigid`).

@group(0) @binding(2) var<storage, read> velocity_sum: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> live: array<u32>;
@group(0) @binding(4) var<storage, read> spin: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> inertia: array<mat3x3<f32>>;
@group(0) @binding(6) var<storage, read_write> mean: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> omega: array<vec4<f32>>;

// floe-engine `solid::cpu::INERTIA_REGULARISATION`.
const INERTIA_REGULARISATION: f32 = 1e-6;
// f32::MIN_POSITIVE.
const TINY: f32 = 1.17549435e-38;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let s = thread_index(gid, groups);
    if (s >= solid.sizes.x) {
        return;
    }
    if (live[s] == 0u) {
        mean[s] = vec4<f32>(0.0);
        omega[s] = vec4<f32>(0.0);
        return;
    }
    let i = inertia[s];
    let add = INERTIA_REGULARISATION * (i[0].x + i[1].y + i[2].z) + TINY;
    let regular = i + mat3x3<f32>(vec3<f32>(add, 0.0, 0.0), vec3<f32>(0.0, add, 0.0), vec3<f32>(0.0, 0.0, add));
    mean[s] = vec4<f32>(velocity_sum[s].xyz / f32(live[s]), 0.0);
    omega[s] = vec4<f32>(mat_inverse(regular) * spin[s].xyz, 0.0);
}
