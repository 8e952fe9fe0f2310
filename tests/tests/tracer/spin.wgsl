// spin = normalize(rot_y(dt) spin) (Hamilton's product, as glam's), frame = R(spin).

@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<storage, read_write> spin: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> frame: array<mat3x3<f32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let half = 0.5 * dt.x;
    let a = vec4<f32>(0.0, sin(half), 0.0, cos(half));
    let b = spin[i];
    let p = vec4<f32>(
        a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
        a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
        a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
        a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    );
    let q = p * (1.0 / sqrt(dot(p, p)));
    spin[i] = q;
    let x2 = q.x + q.x;
    let y2 = q.y + q.y;
    let z2 = q.z + q.z;
    let xx = q.x * x2;
    let xy = q.x * y2;
    let xz = q.x * z2;
    let yy = q.y * y2;
    let yz = q.y * z2;
    let zz = q.z * z2;
    let wx = q.w * x2;
    let wy = q.w * y2;
    let wz = q.w * z2;
    frame[i] = mat3x3<f32>(
        vec3<f32>(1.0 - (yy + zz), xy + wz, xz - wy),
        vec3<f32>(xy - wz, 1.0 - (xx + zz), yz + wx),
        vec3<f32>(xz + wy, yz - wx, 1.0 - (xx + yy)),
    );
}
