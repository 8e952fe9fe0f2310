// ground_height += rise dt, one thread per terrain node.

@group(0) @binding(2) var<uniform> dt: vec4<f32>;
@group(0) @binding(3) var<storage, read_write> ground: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= arrayLength(&ground)) {
        return;
    }
    ground[i] += tracer.rise * dt.x;
}
