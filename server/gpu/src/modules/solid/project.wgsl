// A particle moves by alpha of the weighted mean of its ways (of their sum under
// conserving shares, each already scaled by its cluster's share; times 1 - beta
// where the bodies melt: `blended`), no further than its room (out of the walls);
// its residual is the largest such mean over the iteration's sweeps (floe-engine
// `solid::cpu::Project`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> way: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> weight: array<f32>;
@group(0) @binding(5) var<storage, read_write> pos: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> residual: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        project(i, solid.settings.x);
    }
}

fn project(i: u32, share: f32) {
    var r = residual[i];
    if (sweep.x == 0u) {
        r = 0.0;
    }
    if (weight[i] > 0.0) {
        var mean = way[i].xyz / weight[i];
        if (solid.rigid.y != 0.0) {
            mean = way[i].xyz;
        }
        r = max(r, length(mean));
        let moved = clamp(pos[i].xyz + mean * share, solid.low.xyz, solid.high.xyz);
        pos[i] = vec4<f32>(moved, pos[i].w);
    }
    residual[i] = r;
}
