// Memberships -> segment: dst[s] is the sum of values over segment s's live
// memberships in membership order, word by word in f32, one thread per segment
// and no atomics (floe-engine `maps::cpu::SegmentSum`, the same additions in the
// same order).

@group(0) @binding(2) var<storage, read> start: array<u32>;
@group(0) @binding(3) var<storage, read> len: array<u32>;
@group(0) @binding(4) var<storage, read> live: array<u32>;
@group(0) @binding(5) var<storage, read> values: array<f32>;
@group(0) @binding(6) var<storage, read_write> dst: array<f32>;

fn segment_sum(s: u32, words: u32) {
    if (s >= map.segments) {
        return;
    }
    let k0 = start[s];
    let k1 = k0 + len[s];
    for (var w = 0u; w < words; w++) {
        var sum = 0.0;
        for (var k = k0; k < k1; k++) {
            if (live[k] != 0u) {
                sum += values[k * words + w];
            }
        }
        dst[s * words + w] = sum;
    }
}

@compute @workgroup_size(WG)
fn w1(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    segment_sum(thread_index(gid, groups), 1u);
}

@compute @workgroup_size(WG)
fn w4(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    segment_sum(thread_index(gid, groups), 4u);
}

@compute @workgroup_size(WG)
fn w12(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    segment_sum(thread_index(gid, groups), 12u);
}
