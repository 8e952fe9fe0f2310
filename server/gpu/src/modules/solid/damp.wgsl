// Each particle of a cluster: its velocity moves by the damping (times 1 - beta
// where the bodies melt: `blended`) of the way to the mean of its clusters' rigid
// velocities; the way's length before the move is kept (floe-engine
// `solid::cpu::Damp`).

@group(0) @binding(2) var<storage, read> way: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> weight: array<f32>;
@group(0) @binding(4) var<storage, read_write> nonrigid: array<f32>;
@group(0) @binding(5) var<storage, read_write> vel: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i < params.n) {
        damp(i, solid.rigid.x);
    }
}

fn damp(i: u32, share: f32) {
    var n = 0.0;
    if (weight[i] > 0.0) {
        let to_rigid = way[i].xyz / weight[i] - vel[i].xyz;
        n = length(to_rigid);
        vel[i] = vec4<f32>(vel[i].xyz + to_rigid * share, vel[i].w);
    }
    nonrigid[i] = n;
}
