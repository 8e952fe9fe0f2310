// The solid module's uniform (floe-gpu `modules::solid::uniform`) and the polar
// decompositions of floe-engine `modules::solid::polar`, line for line.

struct Solid {
    // The share of its way an iteration moves a particle by (alpha, or 1 where alpha
    // applies once per step), then the oriented particles' ellipsoid moment (a^2, b^2, c^2) / 5 (m^2).
    settings: vec4<f32>,
    // Clusters, memberships, rotation method (0 iterative, 1 eigen), iterations of the iterative one.
    sizes: vec4<u32>,
    // Solver (SOLVER_*), the colours a cluster's colour is taken modulo, blend (0 QLERP, 1 ExpMap),
    // the weight of a cluster of another colour (SolidConsts::idle_weight: 1 hybrid, else 0).
    solver: vec4<u32>,
    // The room an elastic particle is held in (SolidConsts::room), lower and upper corners (m).
    low: vec4<f32>,
    high: vec4<f32>,
    // The cluster radius (m) in x (as f32), the elastic materials' bits in y, the
    // fewest members a cluster keeps (MIN_MEMBERS) in z, 1 in w where bodies melt.
    melt: vec4<u32>,
    // The damping toward the clusters' rigid motions in x, 1 in y under conserving
    // shares (SolidConsts::conserving), else 0, alpha in z.
    rigid: vec4<f32>,
}

@group(0) @binding(1) var<uniform> solid: Solid;

const SOLVER_JACOBI = 0u;
const SOLVER_WEIGHTED = 1u;
const SOLVER_COLOURED = 2u;

// Whether a cluster of this colour is matched in this sweep (SolidConsts::active).
fn matched(colour: u32, sweep: u32) -> bool {
    return solid.solver.x != SOLVER_COLOURED || colour % solid.solver.y == sweep;
}

// Hamilton's product a b (glam's).
fn quat_mul(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(
        a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
        a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
        a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
        a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    );
}

// The rotation matrix of a unit quaternion (glam's Mat3::from_quat).
fn quat_mat(q: vec4<f32>) -> mat3x3<f32> {
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
    return mat3x3<f32>(
        vec3<f32>(1.0 - (yy + zz), xy + wz, xz - wy),
        vec3<f32>(xy - wz, 1.0 - (xx + zz), yz + wx),
        vec3<f32>(xz + wy, yz - wx, 1.0 - (xx + yy)),
    );
}

// The inertia of a unit mass at r, |r|^2 1 - r r^T (solid::cpu::inertia_of).
fn inertia_of(r: vec3<f32>) -> mat3x3<f32> {
    let l = dot(r, r);
    let diagonal = mat3x3<f32>(vec3<f32>(l, 0.0, 0.0), vec3<f32>(0.0, l, 0.0), vec3<f32>(0.0, 0.0, l));
    return diagonal - mat3x3<f32>(r * r.x, r * r.y, r * r.z);
}

// The inverse of m by its columns' cross products (glam's Mat3::inverse).
fn mat_inverse(m: mat3x3<f32>) -> mat3x3<f32> {
    let t0 = cross(m[1], m[2]);
    let t1 = cross(m[2], m[0]);
    let t2 = cross(m[0], m[1]);
    let inv_det = 1.0 / dot(m[2], t2);
    return transpose(mat3x3<f32>(t0 * inv_det, t1 * inv_det, t2 * inv_det));
}

// A quaternion rotating v (glam's Quat * Vec3).
fn quat_rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    return quat_mat(q) * v;
}

// Mueller et al. 2016, alg. 1 (polar::iterative).
fn polar_iterative(a: mat3x3<f32>, q0: vec4<f32>, iterations: u32) -> vec4<f32> {
    var q = q0;
    for (var k = 0u; k < iterations; k++) {
        let r = quat_mat(q);
        let c = cross(r[0], a[0]) + cross(r[1], a[1]) + cross(r[2], a[2]);
        let d = dot(r[0], a[0]) + dot(r[1], a[1]) + dot(r[2], a[2]);
        let omega = c / (abs(d) + 1e-9);
        let w = length(omega);
        if (w < 1e-9) {
            break;
        }
        let axis = omega / w;
        let turn = vec4<f32>(axis * sin(0.5 * w), cos(0.5 * w));
        let p = quat_mul(turn, q);
        q = p / length(p);
    }
    return q;
}

// The quaternion of a rotation matrix (glam's Quat::from_mat3).
fn mat_quat(m: mat3x3<f32>) -> vec4<f32> {
    let m00 = m[0].x;
    let m01 = m[0].y;
    let m02 = m[0].z;
    let m10 = m[1].x;
    let m11 = m[1].y;
    let m12 = m[1].z;
    let m20 = m[2].x;
    let m21 = m[2].y;
    let m22 = m[2].z;
    if (m22 <= 0.0) {
        let dif10 = m11 - m00;
        let omm22 = 1.0 - m22;
        if (dif10 <= 0.0) {
            let four_xsq = omm22 - dif10;
            let inv4x = 0.5 / sqrt(four_xsq);
            return vec4<f32>(four_xsq * inv4x, (m01 + m10) * inv4x, (m02 + m20) * inv4x, (m12 - m21) * inv4x);
        }
        let four_ysq = omm22 + dif10;
        let inv4y = 0.5 / sqrt(four_ysq);
        return vec4<f32>((m01 + m10) * inv4y, four_ysq * inv4y, (m12 + m21) * inv4y, (m20 - m02) * inv4y);
    }
    let sum11 = m11 + m00;
    let opm22 = 1.0 + m22;
    if (sum11 <= 0.0) {
        let four_zsq = opm22 - sum11;
        let inv4z = 0.5 / sqrt(four_zsq);
        return vec4<f32>((m02 + m20) * inv4z, (m12 + m21) * inv4z, four_zsq * inv4z, (m01 - m10) * inv4z);
    }
    let four_wsq = opm22 + sum11;
    let inv4w = 0.5 / sqrt(four_wsq);
    return vec4<f32>((m12 - m21) * inv4w, (m20 - m02) * inv4w, (m01 - m10) * inv4w, four_wsq * inv4w);
}

/// Below this share of |A v_0| the image of a cluster's second axis is missing: the
/// cluster is straight (polar.rs's STRAIGHT).
const STRAIGHT: f32 = 1e-4;

/// The shortest-arc rotation taking the unit vector a to the unit vector b.
fn arc(a: vec3<f32>, b: vec3<f32>) -> vec4<f32> {
    let d = dot(a, b);
    if (d < -0.999999) {
        // Opposite: half a turn about any axis square to a.
        var axis = cross(vec3<f32>(1.0, 0.0, 0.0), a);
        if (dot(axis, axis) < 1e-6) {
            axis = cross(vec3<f32>(0.0, 1.0, 0.0), a);
        }
        return vec4<f32>(normalize(axis), 0.0);
    }
    let q = vec4<f32>(cross(a, b), 1.0 + d);
    return q / length(q);
}

// The first thesis's polar decomposition (polar::eigen): Jacobi eigenvalue
// rotations of A^T A, R = A V diag(1 / sqrt(l)) V^T as U V^T.
fn polar_eigen(m: mat3x3<f32>) -> vec4<f32> {
    let ata = transpose(m) * m;
    var a: array<array<f32, 3>, 3>;
    var v: array<array<f32, 3>, 3>;
    for (var c = 0; c < 3; c++) {
        for (var r = 0; r < 3; r++) {
            a[c][r] = ata[c][r];
            v[c][r] = select(0.0, 1.0, c == r);
        }
    }
    for (var sweep = 0; sweep < 16; sweep++) {
        let off = abs(a[0][1]) + abs(a[0][2]) + abs(a[1][2]);
        if (off < 1e-20) {
            break;
        }
        for (var pair = 0; pair < 3; pair++) {
            let p = select(select(1, 0, pair < 2), 0, pair == 0);
            let q = select(select(2, 2, pair < 2), 1, pair == 0);
            if (abs(a[p][q]) < 1e-30) {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            var t = sign(theta) / (abs(theta) + sqrt(theta * theta + 1.0));
            if (theta == 0.0) {
                t = 1.0;
            }
            let c = 1.0 / sqrt(t * t + 1.0);
            let s = t * c;
            for (var k = 0; k < 3; k++) {
                let akp = a[k][p];
                let akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for (var k = 0; k < 3; k++) {
                let apk = a[p][k];
                let aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for (var k = 0; k < 3; k++) {
                let vp = v[k][p];
                let vq = v[k][q];
                v[k][p] = c * vp - s * vq;
                v[k][q] = s * vp + c * vq;
            }
        }
    }
    let values = vec3<f32>(a[0][0], a[1][1], a[2][2]);
    // v[k][j]: row k, column j of V.
    let vecs = mat3x3<f32>(
        vec3<f32>(v[0][0], v[1][0], v[2][0]),
        vec3<f32>(v[0][1], v[1][1], v[2][1]),
        vec3<f32>(v[0][2], v[1][2], v[2][2]),
    );
    // The two largest eigenvalues' axes, u_k = A v_k / |A v_k|, and R = U V^T with
    // the third axes their cross products (polar.rs's eigen: a rotation also for
    // flat clusters and where det A < 0; a straight cluster, told by A's images, turns
    // by the shortest arc).
    var i0 = 0;
    var i1 = 1;
    var i2 = 2;
    if (values[i1] > values[i0]) { let t = i0; i0 = i1; i1 = t; }
    if (values[i2] > values[i0]) { let t = i0; i0 = i2; i2 = t; }
    if (values[i2] > values[i1]) { let t = i1; i1 = i2; i2 = t; }
    let v0 = vecs[i0];
    let av0 = m * v0;
    if (dot(av0, av0) == 0.0) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let u0 = normalize(av0);
    let av1 = m * vecs[i1];
    let across = av1 - u0 * dot(u0, av1);
    if (length(across) <= STRAIGHT * length(av0)) {
        return arc(v0, u0);
    }
    let u1 = normalize(across);
    let v1 = normalize(vecs[i1] - v0 * dot(v0, vecs[i1]));
    let u = mat3x3<f32>(u0, u1, cross(u0, u1));
    let w = mat3x3<f32>(v0, v1, cross(v0, v1));
    let q = mat_quat(u * transpose(w));
    return q / length(q);
}
