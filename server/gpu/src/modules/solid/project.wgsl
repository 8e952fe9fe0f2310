// Jacobi: a member moves by alpha of the way to the mean of its goals (floe-engine
// `solid::cpu::Project`); the residual is that way's length.

@group(0) @binding(2) var<storage, read> goal_sum: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> id: array<u32>;
@group(0) @binding(4) var<storage, read> count: array<u32>;
@group(0) @binding(5) var<storage, read_write> residual: array<f32>;
@group(0) @binding(6) var<storage, read_write> pos: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let member = id[i];
    var n = 0u;
    if (member < arrayLength(&count)) {
        n = count[member];
    }
    if (n == 0u) {
        residual[i] = 0.0;
        return;
    }
    let way = goal_sum[i].xyz / f32(n) - pos[i].xyz;
    residual[i] = length(way);
    pos[i] = vec4<f32>(pos[i].xyz + way * solid.settings.x, pos[i].w);
}
