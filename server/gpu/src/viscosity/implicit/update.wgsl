// One step along the search direction (floe-engine
// `viscosity::implicit::Update`): alpha = RZ / PAP, v += alpha p,
// r -= alpha Ap, and per particle the new r.z and r.z / R0Z.

// The solve's scalars: r.z, r.z at the start, p.Ap, the new r.z.
@group(0) @binding(1) var<storage, read> scalars: array<f32>;
@group(0) @binding(2) var<storage, read> dir: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> ap: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> diag: array<f32>;
@group(0) @binding(5) var<storage, read_write> vel: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> res: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> dots: array<f32>;
@group(0) @binding(8) var<storage, read_write> residual: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let alpha = ratio(scalars[0], scalars[2]);
    let v = vel[i];
    vel[i] = vec4<f32>(v.xyz + dir[i].xyz * alpha, v.w);
    let r = res[i].xyz - ap[i].xyz * alpha;
    res[i] = vec4<f32>(r, 0.0);
    let rz = dot(r, r / diag[i]);
    dots[i] = rz;
    residual[i] = ratio(rz, scalars[1]);
}
