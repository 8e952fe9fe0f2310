// Applies the sort's permutation (floe-engine `neighbors::permute`):
// `dst[k] = src[order[k]]`, for the vec4 state and for the particle ids, whose
// pass also records the inverse (`slot_of[id] = k`) for identity-ordered output.

@group(0) @binding(1) var<storage, read> order: array<u32>;
@group(0) @binding(2) var<storage, read> src: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> dst: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> ids_src: array<u32>;
@group(0) @binding(5) var<storage, read_write> ids_dst: array<u32>;
@group(0) @binding(6) var<storage, read_write> slot_of: array<u32>;

@compute @workgroup_size(WG)
fn state(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= params.n) {
        return;
    }
    dst[k] = src[order[k]];
}

@compute @workgroup_size(WG)
fn ids(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= params.n) {
        return;
    }
    let id = ids_src[order[k]];
    ids_dst[k] = id;
    slot_of[id] = k;
}
