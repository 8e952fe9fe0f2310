// One f32 attribute reduced to one number (floe-engine `schemes::Reduction`, the
// residual of an iterative solve, a guard's bound): sum, largest value, largest
// magnitude or how many values are outside [lo, hi] or not finite, by a
// workgroup tree reduction into `parts` and a second pass over the parts. Sums
// are f32 here (the CPU sums in f64): a residual, not a bit-exact figure.

struct Words {
    n: u32,
    stride: u32,
    // 0 sum, 1 max, 2 max of magnitudes, 3 count outside [lo, hi].
    op: u32,
    _pad: u32,
    lo: f32,
    hi: f32,
}

const RW: u32 = 256u;

@group(0) @binding(0) var<uniform> words: Words;
@group(0) @binding(1) var<storage, read> src: array<f32>;
@group(0) @binding(2) var<storage, read_write> parts: array<f32>;

var<workgroup> shared_r: array<f32, RW>;

fn identity() -> f32 {
    if (words.op == 0u) {
        return 0.0;
    }
    if (words.op == 1u) {
        return -3.4028235e38;
    }
    return 0.0;
}

fn combine(a: f32, b: f32) -> f32 {
    if (words.op == 0u || words.op == 3u) {
        return a + b;
    }
    return max(a, b);
}

fn value(x: f32) -> f32 {
    if (words.op == 2u) {
        return abs(x);
    }
    if (words.op == 3u) {
        // Infinite or NaN: all exponent bits set (WGSL has no isnan).
        let non_finite = (bitcast<u32>(x) & 0x7f800000u) == 0x7f800000u;
        return select(0.0, 1.0, non_finite || x < words.lo || x > words.hi);
    }
    return x;
}

fn reduce_workgroup(t: u32) {
    for (var stride = RW / 2u; stride > 0u; stride >>= 1u) {
        workgroupBarrier();
        if (t < stride) {
            shared_r[t] = combine(shared_r[t], shared_r[t + stride]);
        }
    }
    workgroupBarrier();
}

@compute @workgroup_size(RW)
fn partials(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let w = wid.x + wid.y * groups.x;
    let i = w * RW + lid.x;
    var r = identity();
    if (i < words.n) {
        r = value(src[i]);
    }
    shared_r[lid.x] = r;
    reduce_workgroup(lid.x);
    if (lid.x == 0u && w * RW < words.n) {
        parts[w] = shared_r[0];
    }
}

@compute @workgroup_size(RW)
fn total(@builtin(local_invocation_id) lid: vec3<u32>) {
    let count = (words.n + RW - 1u) / RW;
    var r = identity();
    for (var k = lid.x; k < count; k += RW) {
        r = combine(r, parts[k]);
    }
    shared_r[lid.x] = r;
    reduce_workgroup(lid.x);
    if (lid.x == 0u) {
        parts[0] = shared_r[0];
    }
}
