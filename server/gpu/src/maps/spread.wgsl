// Segment -> membership: dst[k] = src[segment[k]], `words` 32-bit words per
// element (floe-engine `maps::cpu::Spread`).

@group(0) @binding(2) var<storage, read> segment: array<u32>;
@group(0) @binding(3) var<storage, read> src: array<u32>;
@group(0) @binding(4) var<storage, read_write> dst: array<u32>;

fn spread(k: u32, words: u32) {
    if (k >= map.memberships) {
        return;
    }
    let s = segment[k];
    for (var w = 0u; w < words; w++) {
        dst[k * words + w] = src[s * words + w];
    }
}

@compute @workgroup_size(WG)
fn w1(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    spread(thread_index(gid, groups), 1u);
}

@compute @workgroup_size(WG)
fn w4(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    spread(thread_index(gid, groups), 4u);
}

@compute @workgroup_size(WG)
fn w12(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    spread(thread_index(gid, groups), 12u);
}
