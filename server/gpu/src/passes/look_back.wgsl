// x = x_start: the positions put back after the position solves' look-ahead
// (floe-engine `position_solve::run_ahead`); the w of x (the material) is kept.

@group(0) @binding(1) var<storage, read> start: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    pos[i] = vec4<f32>(start[i].xyz, pos[i].w);
}
