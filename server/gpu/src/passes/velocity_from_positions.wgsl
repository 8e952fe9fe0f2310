// v += (x - x_predicted) / dt after the position solves (floe-engine
// `position_solve`, the same operations: the difference times 1 / dt).

// The stage's dt (s) in x; y, z, w are 0.
@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> predicted: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> vel: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let inv_dt = 1.0 / dt.x;
    vel[i] = vec4<f32>(vel[i].xyz + (pos[i].xyz - predicted[i].xyz) * inv_dt, vel[i].w);
}
