// The first search direction p = z = r / d, and per particle r.z, twice: summed
// into RZ and into R0Z, the start's for the convergence test (floe-engine
// `viscosity::implicit::Precondition`).

@group(0) @binding(1) var<storage, read> res: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> diag: array<f32>;
@group(0) @binding(3) var<storage, read_write> dir: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> dots: array<f32>;
@group(0) @binding(5) var<storage, read_write> r0z: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let r = res[i].xyz;
    let z = r / diag[i];
    dir[i] = vec4<f32>(z, 0.0);
    dots[i] = dot(r, z);
    r0z[i] = dots[i];
}
