// A_k = (x_k - c) q_k^T per membership of a cluster matched in this sweep
// (floe-engine `solid::cpu::Moment`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> member_x: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> cluster_sum: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> segment: array<u32>;
@group(0) @binding(6) var<storage, read> live: array<u32>;
@group(0) @binding(7) var<storage, read> rest: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> colour: array<u32>;
@group(0) @binding(9) var<storage, read_write> moment: array<mat3x3<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    if (!matched(colour[s], sweep.x)) {
        return;
    }
    let p = member_x[k].xyz - cluster_sum[s].xyz / f32(max(live[s], 1u));
    let q = rest[k].xyz;
    moment[k] = mat3x3<f32>(p * q.x, p * q.y, p * q.z);
}
