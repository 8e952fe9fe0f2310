// Alpha once per step (the first thesis's eq. 2.23): each elastic particle's move
// over the shape solve scaled by alpha, x = x_predicted + alpha (x - x_predicted)
// (floe-engine `solid::cpu::Stiffen`).

@group(0) @binding(2) var<storage, read> predicted: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let p = pos[i];
    if (((solid.melt.y >> material_of(p)) & 1u) == 1u) {
        let before = predicted[i].xyz;
        pos[i] = vec4<f32>(before + (p.xyz - before) * solid.rigid.z, p.w);
    }
}
