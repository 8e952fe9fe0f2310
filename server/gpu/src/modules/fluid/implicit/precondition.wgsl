// The first search direction p = z = r / d, and per particle r.z and b.b / d with
// b = m v* (floe-engine `modules::fluid::implicit::Precondition`).

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> res: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> diag: array<f32>;
@group(0) @binding(5) var<storage, read_write> dir: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> dots: array<f32>;
@group(0) @binding(7) var<storage, read_write> bb: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let r = res[i].xyz;
    let z = r / diag[i];
    let b = vel[i].xyz * params.materials[material_of(pos[i])].y;
    dir[i] = vec4<f32>(z, 0.0);
    dots[i] = dot(r, z);
    bb[i] = dot(b, b) / diag[i];
}
