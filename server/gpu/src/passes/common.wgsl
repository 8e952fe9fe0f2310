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
    inv_cell: f32,
    grid_dims: vec3<u32>,
    cell_count: u32,
    wall_origin: vec3<f32>,
    wall_inv_cell: f32,
    wall_dims: vec3<u32>,
    wall_cell_count: u32,
    gravity: vec3<f32>,
    support: f32,
    domain_min: vec3<f32>,
    h2: f32,
    domain_max: vec3<f32>,
    inv_h: f32,
    w_norm: f32,
    g_norm: f32,
    n_materials: u32,
    // Index of the wall grid's first run start in `starts` (after the particle grid's).
    wall_start: u32,
    // Per material: rest density (kg/m^3), mass (kg), 1 / rho0^2, rho0 / rho0 of material 0.
    materials: array<vec4<f32>, 16>,
}

const WG: u32 = 128u;
const KERNEL_MUELLER: u32 = 0u;

@group(0) @binding(0) var<uniform> params: Params;

// Dispatches wider than 65535 workgroups use a second dimension.
fn thread_index(gid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return gid.x + gid.y * groups.x * WG;
}

// The 3x3x3 block of cells around `p` (clamped to the grid), as corner cells.
struct Block {
    lo: vec3<u32>,
    hi: vec3<u32>,
}

fn cell_coords(p: vec3<f32>, origin: vec3<f32>, inv_cell: f32, dims: vec3<u32>) -> vec3<u32> {
    let c = (p - origin) * inv_cell;
    return min(vec3<u32>(max(c, vec3<f32>(0.0))), dims - vec3<u32>(1u));
}

fn cell_index(c: vec3<u32>, dims: vec3<u32>) -> u32 {
    return c.x + dims.x * (c.y + dims.y * c.z);
}

fn block_of(p: vec3<f32>, origin: vec3<f32>, inv_cell: f32, dims: vec3<u32>) -> Block {
    let c = cell_coords(p, origin, inv_cell, dims);
    return Block(max(c, vec3<u32>(1u)) - vec3<u32>(1u), min(c + vec3<u32>(1u), dims - vec3<u32>(1u)));
}

// Run k (0..9, z outer, y inner) of a block: the cell range whose particles are
// contiguous after the sort, as (first cell, last cell + 1); (0, 0) when the
// block is clamped and has no such row.
fn run_cells(b: Block, k: u32, dims: vec3<u32>) -> vec2<u32> {
    let z = b.lo.z + k / 3u;
    let y = b.lo.y + k % 3u;
    if (z > b.hi.z || y > b.hi.y) {
        return vec2<u32>(0u, 0u);
    }
    let row = dims.x * (y + dims.y * z);
    return vec2<u32>(row + b.lo.x, row + b.hi.x + 1u);
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
    let inner = 6.0 * q * q * (q - 1.0) + 1.0;
    let t = 1.0 - q;
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
    return params.g_norm * select(-t * t, q * (3.0 * q - 2.0), q <= 0.5);
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
