// x_start = x, then x += dt v: the positions the velocities would reach, for the
// position solves a scheme runs before its pressure solve (floe-engine
// `position_solve::run_ahead`, the same operations). The w of x (the material)
// is kept.

// The stage's dt (s) in x; y, z, w are 0.
@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> start: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    start[i] = pos[i];
    pos[i] = vec4<f32>(pos[i].xyz + vel[i].xyz * dt.x, pos[i].w);
}
