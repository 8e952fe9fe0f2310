// Shared by every particle kernel (prepended to each kernel's source): the
// scene constants with the material table, the grid and the SPH kernels,
// mirroring floe-engine's `neighbors` and `kernel` modules line for line so the
// CPU backend can serve as the oracle.

struct Params {
    n: u32,
    n_walls: u32,
    n_constraints: u32,
    kernel_kind: u32,
    grid_origin: vec3<f32>,
    cell_count: u32,
    grid_inv_cell: vec3<f32>,
    wall_cell_count: u32,
    grid_dims: vec3<u32>,
    // Bit a set when axis a is periodic.
    periodic: u32,
    wall_origin: vec3<f32>,
    // Index of the wall grid's first run start in `starts` (after the particle grid's).
    wall_start: u32,
    wall_inv_cell: vec3<f32>,
    n_materials: u32,
    wall_dims: vec3<u32>,
    w_norm: f32,
    gravity: vec3<f32>,
    support: f32,
    domain_min: vec3<f32>,
    h2: f32,
    domain_max: vec3<f32>,
    inv_h: f32,
    // Period per axis (m), 0 on open axes.
    period: vec3<f32>,
    g_norm: f32,
    // Half the period (m), the largest float on open axes.
    half_period: vec3<f32>,
    _pad: u32,
    // Per material: rest density (kg/m^3), mass (kg), 1 / rho0^2, rho0 / rho0 of material 0.
    materials: array<vec4<f32>, 16>,
}

const WG: u32 = 128u;
const KERNEL_MUELLER: u32 = 0u;
const KERNEL_WENDLAND: u32 = 2u;

@group(0) @binding(0) var<uniform> params: Params;

// Dispatches wider than 65535 workgroups use a second dimension.
fn thread_index(gid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return gid.x + gid.y * groups.x * WG;
}

// The 3x3x3 block of cells around `p` (floe-engine `Grid::for_each_run`): on y and z
// its distinct cells (clamped to the grid on an open axis, wrapped around on a
// periodic one), on x one or two runs of contiguous cells (two where it wraps).
struct Block {
    xs: vec4<u32>,
    ys: vec3<u32>,
    zs: vec3<u32>,
    // Runs along x, cells along y and z.
    counts: vec3<u32>,
}

fn cell_coords(p: vec3<f32>, origin: vec3<f32>, inv_cell: vec3<f32>, dims: vec3<u32>) -> vec3<u32> {
    let c = (p - origin) * inv_cell;
    return min(vec3<u32>(max(c, vec3<f32>(0.0))), dims - vec3<u32>(1u));
}

fn cell_index(c: vec3<u32>, dims: vec3<u32>) -> u32 {
    return c.x + dims.x * (c.y + dims.y * c.z);
}

fn wraps(axis: u32) -> bool {
    return (params.periodic & (1u << axis)) != 0u;
}

// Back through the opposite face on periodic axes (floe-engine `Periodicity::wrap`).
fn wrap_periodic(p: vec3<f32>) -> vec3<f32> {
    var x = p;
    for (var axis = 0u; axis < 3u; axis++) {
        let lo = params.domain_min[axis];
        let l = params.period[axis];
        if (wraps(axis) && (x[axis] < lo || x[axis] >= lo + l)) {
            x[axis] -= l * floor((x[axis] - lo) / l);
            if (x[axis] >= lo + l) {
                x[axis] = lo;
            }
        }
    }
    return x;
}

// The distinct cells around cell `c` along an axis of `d` cells, and how many.
fn block_axis(c: u32, d: u32, wrap: bool) -> vec4<u32> {
    if (!wrap) {
        let lo = max(c, 1u) - 1u;
        let hi = min(c + 1u, d - 1u);
        return vec4<u32>(lo, lo + 1u, hi, hi - lo + 1u);
    }
    if (d < 3u) {
        return vec4<u32>(0u, 1u, 0u, d);
    }
    return vec4<u32>((c + d - 1u) % d, c, (c + 1u) % d, 3u);
}

fn block_of(p: vec3<f32>, origin: vec3<f32>, inv_cell: vec3<f32>, dims: vec3<u32>) -> Block {
    let c = cell_coords(p, origin, inv_cell, dims);
    let y = block_axis(c.y, dims.y, wraps(1u));
    let z = block_axis(c.z, dims.z, wraps(2u));
    let d = dims.x;
    var xs = vec4<u32>(max(c.x, 1u) - 1u, min(c.x + 1u, d - 1u), 0u, 0u);
    var nx = 1u;
    if (wraps(0u)) {
        if (d < 3u) {
            xs = vec4<u32>(0u, d - 1u, 0u, 0u);
        } else if (c.x == 0u) {
            xs = vec4<u32>(0u, 1u, d - 1u, d - 1u);
            nx = 2u;
        } else if (c.x == d - 1u) {
            xs = vec4<u32>(d - 2u, d - 1u, 0u, 0u);
            nx = 2u;
        }
    }
    return Block(xs, y.xyz, z.xyz, vec3<u32>(nx, y.w, z.w));
}

// Runs in a block.
fn block_runs(b: Block) -> u32 {
    return b.counts.x * b.counts.y * b.counts.z;
}

// Run k of a block (x runs innermost, then y, then z, as on the CPU): the cell range
// whose particles are contiguous after the sort, as (first cell, last cell + 1).
fn run_cells(b: Block, k: u32, dims: vec3<u32>) -> vec2<u32> {
    let ix = k % b.counts.x;
    let rest = k / b.counts.x;
    let y = b.ys[rest % b.counts.y];
    let z = b.zs[rest / b.counts.y];
    let row = dims.x * (y + dims.y * z);
    let x = select(b.xs.xy, b.xs.zw, ix == 1u);
    return vec2<u32>(row + x.x, row + x.y + 1u);
}

// The separation `a - b` of two positions, its minimum image on periodic axes
// (floe-engine `Periodicity::image`).
fn separation(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let d = a - b;
    let below = select(d, d + params.period, d < -params.half_period);
    return select(below, d - params.period, d > params.half_period);
}

fn kernel_w(r2: f32) -> f32 {
    if (r2 >= params.h2) {
        return 0.0;
    }
    if (params.kernel_kind == KERNEL_MUELLER) {
        let d = params.h2 - r2;
        return params.w_norm * d * d * d;
    }
    let q = sqrt(r2) * params.inv_h;
    let t = 1.0 - q;
    if (params.kernel_kind == KERNEL_WENDLAND) {
        return params.w_norm * t * t * t * t * (1.0 + 4.0 * q);
    }
    let inner = 6.0 * q * q * (q - 1.0) + 1.0;
    return params.w_norm * select(2.0 * t * t * t, inner, q <= 0.5);
}

fn kernel_dw_dr(r: f32) -> f32 {
    if (r >= params.support) {
        return 0.0;
    }
    if (params.kernel_kind == KERNEL_MUELLER) {
        let d = params.support - r;
        return -params.g_norm * d * d;
    }
    let q = r * params.inv_h;
    let t = 1.0 - q;
    if (params.kernel_kind == KERNEL_WENDLAND) {
        return -params.g_norm * q * t * t * t;
    }
    return params.g_norm * select(-t * t, q * (3.0 * q - 2.0), q <= 0.5);
}

/// The kernel's gradient at separation `x` (`r2 = |x|^2 > 0`): `x (dW/dr) / r`,
/// the same expression the CPU's passes evaluate.
fn kernel_grad(x: vec3<f32>, r2: f32) -> vec3<f32> {
    let r = sqrt(r2);
    return x * (kernel_dw_dr(r) / r);
}

fn kernel_laplacian(r: f32) -> f32 {
    if (r >= params.support) {
        return 0.0;
    }
    if (params.kernel_kind == KERNEL_MUELLER) {
        return params.g_norm * (params.support - r);
    }
    return -2.0 * kernel_dw_dr(r) * r / (r * r + 0.01 * params.h2);
}

// The material of a particle: its index is stored in the w component of its position.
fn material_of(p: vec4<f32>) -> u32 {
    return u32(p.w);
}

// Whether an f32 is infinite or NaN (WGSL has no isinf/isnan).
fn non_finite(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7f800000u) == 0x7f800000u;
}

// a / b, or 0 where b is not positive (a conjugate-gradient solve with nothing
// left to solve; floe-engine `viscosity::implicit::ratio`, `schemes::dfsph::cg::ratio`).
fn ratio(a: f32, b: f32) -> f32 {
    if (b > 0.0) {
        return a / b;
    }
    return 0.0;
}
