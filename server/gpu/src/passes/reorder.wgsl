// Applies the sort's permutation to one attribute of any element type
// (floe-engine `Attrs::permute`): over 32-bit words, `dst[k s + c] = src[order[k] s + c]`
// with `s` words per element; and rebuilds the slot of each id, `slot_of[ids[k]] = k`.

struct Words {
    n: u32,
    stride: u32,
    op: u32,
    _pad: u32,
    lo: f32,
    hi: f32,
}

@group(0) @binding(0) var<uniform> words: Words;
@group(0) @binding(1) var<storage, read> order: array<u32>;
@group(0) @binding(2) var<storage, read> src: array<u32>;
@group(0) @binding(3) var<storage, read_write> dst: array<u32>;

const WG: u32 = 128u;

@compute @workgroup_size(WG)
fn permute(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let t = gid.x + gid.y * groups.x * WG;
    if (t >= words.n * words.stride) {
        return;
    }
    let k = t / words.stride;
    let c = t - k * words.stride;
    dst[t] = src[order[k] * words.stride + c];
}

// Here `src` holds the ids (in slot order) and `dst` the slot of each id.
@compute @workgroup_size(WG)
fn slots(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = gid.x + gid.y * groups.x * WG;
    if (k >= words.n) {
        return;
    }
    dst[src[k]] = k;
}
