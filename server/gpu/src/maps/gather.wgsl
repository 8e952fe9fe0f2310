// Member -> membership: dst[k] = src[slot of member[k]], `words` 32-bit words per
// element (floe-engine `maps::cpu::Gather`).

@group(0) @binding(2) var<storage, read> member: array<u32>;
@group(0) @binding(3) var<storage, read> slot_of: array<u32>;
@group(0) @binding(4) var<storage, read> src: array<u32>;
@group(0) @binding(5) var<storage, read_write> dst: array<u32>;

fn gather(k: u32, words: u32) {
    if (k >= map.memberships) {
        return;
    }
    var j = member[k];
    if (map.sorted != 0u) {
        j = slot_of[j];
    }
    for (var w = 0u; w < words; w++) {
        dst[k * words + w] = src[j * words + w];
    }
}

@compute @workgroup_size(WG)
fn w1(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    gather(thread_index(gid, groups), 1u);
}

@compute @workgroup_size(WG)
fn w4(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    gather(thread_index(gid, groups), 4u);
}

@compute @workgroup_size(WG)
fn w12(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    gather(thread_index(gid, groups), 12u);
}
