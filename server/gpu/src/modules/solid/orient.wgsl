// The oriented particles' quaternion helpers (floe-engine `solid::orient`).

// The conjugate (inverse) of a unit quaternion.
fn quat_conj(q: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(-q.xyz, q.w);
}

// q or -q, the one with w >= 0 (orient::short).
fn quat_short(q: vec4<f32>) -> vec4<f32> {
    return select(q, -q, q.w < 0.0);
}

// The rotation by |w| dt about w (orient::turn).
fn quat_turn(w: vec3<f32>, step: f32) -> vec4<f32> {
    let speed = length(w);
    if (speed < 1e-9) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let half = 0.5 * speed * step;
    return vec4<f32>(w / speed * sin(half), cos(half));
}

// Half the rotation vector of a unit quaternion with w >= 0 (orient::log).
fn quat_log(q: vec4<f32>) -> vec3<f32> {
    let s = length(q.xyz);
    if (s < 1e-9) {
        return q.xyz;
    }
    return q.xyz / s * atan2(s, q.w);
}

// The unit quaternion whose logarithm is v (orient::exp).
fn quat_exp(v: vec3<f32>) -> vec4<f32> {
    let theta = length(v);
    if (theta < 1e-9) {
        return normalize(vec4<f32>(v, 1.0));
    }
    return vec4<f32>(v / theta * sin(theta), cos(theta));
}

// The angular velocity turning `before` into `after` in `step` (orient::spin).
fn quat_spin(after: vec4<f32>, before: vec4<f32>, step: f32) -> vec3<f32> {
    let r = quat_short(quat_mul(after, quat_conj(before)));
    let s = length(r.xyz);
    let angle = 2.0 * atan2(s, r.w);
    if (angle < 1e-9 || step <= 0.0) {
        return vec3<f32>(0.0);
    }
    return r.xyz / s * (angle / step);
}
