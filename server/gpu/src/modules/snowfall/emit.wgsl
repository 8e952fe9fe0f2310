// The step's births (floe-engine `snowfall::flakes::emit`): one thread.

@group(0) @binding(2) var<uniform> dt: vec4<f32>;
@group(0) @binding(3) var<storage, read_write> tally: array<u32>;
@group(0) @binding(4) var<storage, read_write> timer: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    if (thread_index(gid, groups) != 0u) {
        return;
    }
    let owed = snowfall.fall.z * dt.x;
    let carry = timer[0] + owed;
    let born = floor(carry);
    timer[0] = carry - born;
    timer[1] = timer[1] + dt.x;
    tally[1] = tally[0];
    tally[2] = u32(born);
    tally[0] = tally[0] + u32(born);
}
