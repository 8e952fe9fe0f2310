// The XSPH kick (floe-engine `modules::fluid::xsph`): the correction xsph.wgsl
// summed, added to the velocity after the kick that follows an evaluation.

@group(0) @binding(1) var<storage, read> xsph: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> vel: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    vel[i] = vec4<f32>(vel[i].xyz + xsph[i].xyz, 0.0);
}
