// The next search direction p = r / d + (RZ_NEW / RZ) p (floe-engine
// `viscosity::implicit::Direction`).

// The solve's scalars: r.z, r.z at the start, p.Ap, the new r.z.
@group(0) @binding(1) var<storage, read> scalars: array<f32>;
@group(0) @binding(2) var<storage, read> res: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> diag: array<f32>;
@group(0) @binding(4) var<storage, read_write> dir: array<vec4<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let beta = ratio(scalars[3], scalars[0]);
    dir[i] = vec4<f32>(res[i].xyz / diag[i] + dir[i].xyz * beta, 0.0);
}
