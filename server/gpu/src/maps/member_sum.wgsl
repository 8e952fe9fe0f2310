// Memberships -> member: dst[i] is the sum of values over the live memberships of
// the member in slot i, in membership order, word by word in f32, one thread per
// member and no atomics (floe-engine `maps::cpu::MemberSum`).

@group(0) @binding(2) var<storage, read> first: array<u32>;
@group(0) @binding(3) var<storage, read> count: array<u32>;
@group(0) @binding(4) var<storage, read> order: array<u32>;
@group(0) @binding(5) var<storage, read> live: array<u32>;
@group(0) @binding(6) var<storage, read> id: array<u32>;
@group(0) @binding(7) var<storage, read> values: array<f32>;
@group(0) @binding(8) var<storage, read_write> dst: array<f32>;

fn member_sum(i: u32, words: u32) {
    if (i >= map.members) {
        return;
    }
    var j = i;
    if (map.sorted != 0u) {
        j = id[i];
    }
    let e0 = first[j];
    let e1 = e0 + count[j];
    for (var w = 0u; w < words; w++) {
        var sum = 0.0;
        for (var e = e0; e < e1; e++) {
            let k = order[e];
            if (live[k] != 0u) {
                sum += values[k * words + w];
            }
        }
        dst[i * words + w] = sum;
    }
}

@compute @workgroup_size(WG)
fn w1(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    member_sum(thread_index(gid, groups), 1u);
}

@compute @workgroup_size(WG)
fn w4(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    member_sum(thread_index(gid, groups), 4u);
}

@compute @workgroup_size(WG)
fn w12(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    member_sum(thread_index(gid, groups), 12u);
}
