// Exclusive prefix sum of a u32 array (counting sort's cell starts), in blocks
// of 512 values per workgroup: `scan_blocks` scans each block and writes its
// total to `block_sums`; those totals are scanned the same way (recursively,
// by the host) and `add_block_sums` adds each block's offset back.
// Hillis & Steele 1986 (Commun. ACM 29(12)) within a workgroup.

struct ScanParams {
    len: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

const THREADS: u32 = 256u;
const BLOCK: u32 = 512u;

@group(0) @binding(0) var<uniform> scan: ScanParams;
@group(0) @binding(1) var<storage, read_write> data: array<u32>;
@group(0) @binding(2) var<storage, read_write> block_sums: array<u32>;

var<workgroup> partial: array<u32, THREADS>;

@compute @workgroup_size(THREADS)
fn scan_blocks(@builtin(local_invocation_id) lid: vec3<u32>, @builtin(workgroup_id) wid: vec3<u32>) {
    let t = lid.x;
    let a = wid.x * BLOCK + 2u * t;
    var e0 = 0u;
    var e1 = 0u;
    if (a < scan.len) {
        e0 = data[a];
    }
    if (a + 1u < scan.len) {
        e1 = data[a + 1u];
    }
    partial[t] = e0 + e1;
    workgroupBarrier();
    for (var off = 1u; off < THREADS; off <<= 1u) {
        var v = partial[t];
        if (t >= off) {
            v += partial[t - off];
        }
        workgroupBarrier();
        partial[t] = v;
        workgroupBarrier();
    }
    let before = partial[t] - e0 - e1;
    if (a < scan.len) {
        data[a] = before;
    }
    if (a + 1u < scan.len) {
        data[a + 1u] = before + e0;
    }
    if (t == THREADS - 1u) {
        block_sums[wid.x] = partial[t];
    }
}

@compute @workgroup_size(THREADS)
fn add_block_sums(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * THREADS;
    if (i < scan.len) {
        data[i] += block_sums[i / BLOCK];
    }
}
