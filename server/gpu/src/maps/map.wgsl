// Prepended to the generic map kernels (after common.wgsl): the map's counts
// (floe-engine `maps::Counts`), a uniform named after the map.

struct Map {
    segments: u32,
    memberships: u32,
    members: u32,
    // 1 when members are particles, addressed by stable id through `slot_of`.
    sorted: u32,
}

@group(0) @binding(1) var<uniform> map: Map;
