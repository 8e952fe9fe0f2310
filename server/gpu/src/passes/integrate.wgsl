// The integrators' two halves (floe-engine `cpu::core::kick` and `drift`):
// `kick` updates velocities, `drift` positions (moving with `v + dt/2 a_transport`
// in scenes with a transport velocity) followed by the walls'
// non-penetration constraints (floe-engine `boundary::WallConstraint::apply`), a
// terrain's with Coulomb friction (floe-engine `terrain::TerrainConstraint::apply`).

struct Step {
    // dt of the kick (s).
    kick_dt: f32,
    // Damping factor exp(-rate dt) applied with the kick.
    keep: f32,
    // dt of the drift (s).
    drift_dt: f32,
    // 1 when the drift adds `dt/2 a_transport` to the velocity it moves with.
    transport: u32,
}

// A wall's constraint. kind 0, a box: `a` its lower and `b` its upper interior
// corner, `closed` bit 2*axis+side set for each closed face. kind 1, a plane:
// `a` its centre, `b` its unit normal into the fluid, `t1`/`t2` unit tangents
// with their half edge lengths in w. kind 2, a terrain: `a` the height grid's lower
// corner (x, z) and node spacing (x, z), `b` the friction coefficient, the contact
// distance and the nodes along x and z, `closed` the index of its first height.
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
// The kick: accelerations; the drift: the walls' constraints and the ground's
// heights (`ground_height`, every terrain's nodes; one layout each).
@group(0) @binding(4) var<storage, read> acc: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> constraints: array<Constraint>;
@group(0) @binding(6) var<storage, read> heights: array<f32>;
// The drift's transport accelerations (`acc` again in scenes without them).
@group(0) @binding(7) var<storage, read> transport: array<vec4<f32>>;

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

// A terrain's height (x) and unit upward normal (yzw) at (x, z): bilinear in the
// grid's cell (floe-engine `terrain::HeightGrid::eval`).
fn terrain_eval(c: Constraint, x: f32, z: f32) -> vec4<f32> {
    let nx = u32(c.b.z);
    let nz = u32(c.b.w);
    let u = clamp((x - c.a.x) / c.a.z, 0.0, f32(nx - 1u));
    let w = clamp((z - c.a.y) / c.a.w, 0.0, f32(nz - 1u));
    let i = min(u32(floor(u)), nx - 2u);
    let k = min(u32(floor(w)), nz - 2u);
    let fu = u - f32(i);
    let fw = w - f32(k);
    let base = c.closed + k * nx + i;
    let h00 = heights[base];
    let h10 = heights[base + 1u];
    let h01 = heights[base + nx];
    let h11 = heights[base + nx + 1u];
    let h = (h00 * (1.0 - fu) + h10 * fu) * (1.0 - fw) + (h01 * (1.0 - fu) + h11 * fu) * fw;
    let dx = ((h10 - h00) * (1.0 - fw) + (h11 - h01) * fw) / c.a.z;
    let dz = ((h01 - h00) * (1.0 - fu) + (h11 - h10) * fu) / c.a.w;
    return vec4<f32>(h, normalize(vec3<f32>(-dx, 1.0, -dz)));
}

@compute @workgroup_size(WG)
fn drift(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    var v = vel[i].xyz;
    var moves = v;
    if (step.transport != 0u) {
        moves = v + transport[i].xyz * (0.5 * step.drift_dt);
    }
    var x = pos[i].xyz + moves * step.drift_dt;
    let g_dt = params.gravity * step.drift_dt;
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
        } else if (c.kind == 2u) {
            let nx = u32(c.b.z);
            let nz = u32(c.b.w);
            let hi = c.a.xy + c.a.zw * vec2<f32>(f32(nx - 1u), f32(nz - 1u));
            if (x.x < c.a.x || x.x > hi.x || x.z < c.a.y || x.z > hi.y) {
                continue;
            }
            let e = terrain_eval(c, x.x, x.z);
            let n = e.yzw;
            var removed = 0.0;
            if (x.y < e.x) {
                x.y = e.x;
                let vn = dot(v, n);
                if (vn < 0.0) {
                    v -= n * vn;
                    removed = -vn;
                }
            }
            if ((x.y - e.x) * n.y >= c.b.y) {
                continue;
            }
            let load = removed + max(-dot(g_dt, n), 0.0);
            let vn = dot(v, n);
            let tangential = v - n * vn;
            let speed = length(tangential);
            if (speed > 0.0) {
                let keep = max(speed - c.b.x * load, 0.0) / speed;
                v = n * vn + tangential * keep;
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
    // w keeps the particle's material.
    pos[i] = vec4<f32>(wrap_periodic(x), pos[i].w);
    vel[i] = vec4<f32>(v, 0.0);
}
