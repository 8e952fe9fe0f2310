// The integrators' two halves (floe-engine `cpu::core::kick` and `drift`):
// `kick` updates velocities, `drift` positions followed by the walls'
// non-penetration constraints (floe-engine `boundary::WallConstraint::apply`).

struct Step {
    // dt of the kick (s).
    kick_dt: f32,
    // Damping factor exp(-rate dt) applied with the kick.
    keep: f32,
    // dt of the drift (s).
    drift_dt: f32,
    _pad: f32,
}

// A wall's constraint. kind 0, a box: `a` its lower and `b` its upper interior
// corner, `closed` bit 2*axis+side set for each closed face. kind 1, a plane:
// `a` its centre, `b` its unit normal into the fluid, `t1`/`t2` unit tangents
// with their half edge lengths in w.
struct Constraint {
    kind: u32,
    closed: u32,
    reach: f32,
    _pad: u32,
    a: vec4<f32>,
    b: vec4<f32>,
    t1: vec4<f32>,
    t2: vec4<f32>,
}

@group(0) @binding(1) var<uniform> step: Step;
@group(0) @binding(2) var<storage, read_write> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> vel: array<vec4<f32>>;
// The kick: accelerations; the drift: the walls' constraints (one layout each).
@group(0) @binding(4) var<storage, read> acc: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> constraints: array<Constraint>;

@compute @workgroup_size(WG)
fn kick(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    vel[i] = vec4<f32>((vel[i].xyz + acc[i].xyz * step.kick_dt) * step.keep, 0.0);
}

fn closed(c: Constraint, axis: u32, side: u32) -> bool {
    return (c.closed & (1u << (2u * axis + side))) != 0u;
}

@compute @workgroup_size(WG)
fn drift(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    var v = vel[i].xyz;
    var x = pos[i].xyz + v * step.drift_dt;
    for (var k = 0u; k < params.n_constraints; k++) {
        let c = constraints[k];
        if (c.kind == 0u) {
            let lo = c.a.xyz;
            let hi = c.b.xyz;
            if (any(x < lo - vec3<f32>(c.reach)) || any(x > hi + vec3<f32>(c.reach))) {
                continue;
            }
            for (var axis = 0u; axis < 3u; axis++) {
                if (closed(c, axis, 0u) && x[axis] < lo[axis]) {
                    x[axis] = lo[axis];
                    v[axis] = max(v[axis], 0.0);
                }
                if (closed(c, axis, 1u) && x[axis] > hi[axis]) {
                    x[axis] = hi[axis];
                    v[axis] = min(v[axis], 0.0);
                }
            }
        } else {
            let n = c.b.xyz;
            let rel = x - c.a.xyz;
            let depth = dot(rel, n);
            if (depth >= 0.0 || depth < -c.reach) {
                continue;
            }
            if (abs(dot(rel, c.t1.xyz)) > c.t1.w || abs(dot(rel, c.t2.xyz)) > c.t2.w) {
                continue;
            }
            x -= n * depth;
            let vn = dot(v, n);
            if (vn < 0.0) {
                v -= n * vn;
            }
        }
    }
    // Back through the opposite face on periodic axes (floe-engine `Periodicity::wrap`).
    for (var axis = 0u; axis < 3u; axis++) {
        let lo = params.domain_min[axis];
        let l = params.period[axis];
        if (wraps(axis) && (x[axis] < lo || x[axis] >= lo + l)) {
            x[axis] -= l * floor((x[axis] - lo) / l);
            if (x[axis] >= lo + l) {
                x[axis] = lo;
            }
        }
    }
    // w keeps the particle's material.
    pos[i] = vec4<f32>(x, pos[i].w);
    vel[i] = vec4<f32>(v, 0.0);
}
