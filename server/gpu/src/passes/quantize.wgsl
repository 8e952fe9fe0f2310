// Frame positions quantised on the GPU (floe-engine `quantize::PositionGrid`,
// the frame codec's formula): code = min(floor((x - min) scale + 0.5), top),
// NaN and negatives to 0; written in identity order as 16-bit codes, two
// particles per three u32 (x0 y0 | z0 x1 | y1 z1, low half first), so the
// readback is 6 bytes per particle.

struct QuantGrid {
    min: vec3<f32>,
    top: f32,
    scale: vec3<f32>,
    _pad: f32,
}

@group(0) @binding(1) var<uniform> grid: QuantGrid;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> slot_of: array<u32>;
@group(0) @binding(4) var<storage, read_write> codes: array<u32>;

fn code(v: f32, axis: u32) -> u32 {
    let x = (v - grid.min[axis]) * grid.scale[axis] + 0.5;
    if (x >= grid.top) {
        return u32(grid.top);
    }
    // Also false for NaN.
    if (!(x >= 0.0)) {
        return 0u;
    }
    return u32(x);
}

fn codes_of(id: u32) -> vec3<u32> {
    if (id >= params.n) {
        return vec3<u32>(0u);
    }
    let x = pos[slot_of[id]].xyz;
    return vec3<u32>(code(x.x, 0u), code(x.y, 1u), code(x.z, 2u));
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (2u * k >= params.n) {
        return;
    }
    let a = codes_of(2u * k);
    let b = codes_of(2u * k + 1u);
    codes[3u * k] = a.x | (a.y << 16u);
    codes[3u * k + 1u] = a.z | (b.x << 16u);
    codes[3u * k + 2u] = b.y | (b.z << 16u);
}
