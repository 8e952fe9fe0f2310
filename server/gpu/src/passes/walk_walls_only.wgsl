// The neighbour walk (walk.wgsl's hooks) of a pass that reads the wall neighbours
// alone: `walk_begin`, `walk_wall` for each wall particle within the support
// (walk_walls.wgsl), `walk_end`; no fluid neighbour is visited and `walk_pair` is
// never called.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    walk_begin(i);
    walk_wall_neighbours(i, pos[i].xyz);
    walk_end(i);
}
