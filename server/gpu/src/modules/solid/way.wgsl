// Per membership: the way to its goal, R q_k + c - x_k, and its weight (1; its
// length under weighted Jacobi; the way times its cluster's share, w of its
// centre, under conserving shares); a cluster of another colour has none and the
// idle weight (floe-engine `solid::cpu::Way`).

@group(0) @binding(2) var<uniform> sweep: vec4<u32>;
@group(0) @binding(3) var<storage, read> rotation: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> centre: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> colour: array<u32>;
@group(0) @binding(6) var<storage, read> segment: array<u32>;
@group(0) @binding(7) var<storage, read> rest: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> relative: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> way: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> weight: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(gid, groups);
    if (k >= solid.sizes.y) {
        return;
    }
    let s = segment[k];
    if (!matched(colour[s], sweep.x)) {
        way[k] = vec4<f32>(0.0);
        weight[k] = f32(solid.solver.w);
        return;
    }
    let to_goal = quat_rotate(rotation[s], rest[k].xyz) - (relative[k].xyz - centre[s].xyz);
    // Weighted Jacobi: the way alone and its length, which solid.weigh turns into
    // its cluster's deformation.
    var w = 1.0;
    if (solid.solver.x == SOLVER_WEIGHTED) {
        w = length(to_goal);
    }
    var scale = 1.0;
    if (solid.rigid.y != 0.0) {
        scale = centre[s].w;
    }
    way[k] = vec4<f32>(to_goal * scale, 0.0);
    weight[k] = w;
}
