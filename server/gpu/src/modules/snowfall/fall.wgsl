// Moves, lands and bears the flakes (floe-engine `snowfall::Fall`): a thread per
// slot; landings counted with integer atomics, so the counts do not depend on the
// threads' order.

@group(0) @binding(2) var<uniform> dt: vec4<f32>;
@group(0) @binding(3) var<storage, read_write> flake_x: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> flake_v: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> flake_age: array<f32>;
@group(0) @binding(6) var<storage, read_write> tally: array<atomic<u32>>;
@group(0) @binding(7) var<storage, read> timer: array<f32>;
@group(0) @binding(8) var<storage, read> surface: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> ground_count: array<atomic<u32>>;
@group(0) @binding(10) var<storage, read_write> top_count: array<atomic<u32>>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    let n = snowfall.sizes.x;
    if (i >= n) {
        return;
    }
    let first = atomicLoad(&tally[1]);
    let born = atomicLoad(&tally[2]);
    let w = wind(timer[1]);
    let target_v = vec3<f32>(w.x, -snowfall.fall.w, w.y);
    let d = (i + n - first % n) % n;
    if (d < born) {
        flake_x[i] = vec4<f32>(birth(first + d), 0.0);
        flake_v[i] = vec4<f32>(target_v, AIRBORNE);
        flake_age[i] = 0.0;
        return;
    }
    if (flake_v[i].w != AIRBORNE) {
        return;
    }
    let decay = exp(-dt.x / snowfall.air.x);
    let age = flake_age[i] + dt.x;
    flake_age[i] = age;
    let x0 = flake_x[i].xyz;
    let r = flutter(x0, age);
    let gust = turbulence(x0.x, x0.z, timer[1]);
    let air = target_v + vec3<f32>(gust.x, 0.0, gust.y);
    let vel = air + (flake_v[i].xyz - air) * decay + r * dt.x;
    let p = x0 + vel * dt.x;
    var state = AIRBORNE;
    var at = p;
    if (!over(snowfall.area, p)) {
        if (!over(snowfall.emit, p) || p.y <= snowfall.fall.y || age > snowfall.more.z) {
            state = LEFT;
            atomicAdd(&tally[3], 1u);
        }
    } else {
        let k = cell_of(p.x, p.z);
        let cover = surface[k];
        var top = object_top(x0.y, p, cover.y);
        if (top == NO_TOP) {
            top = column_top(cover.zw, x0.y, p.y, cover.y);
        }
        if (top != NO_TOP) {
            state = LANDED;
            at.y = top;
            atomicAdd(&top_count[k], 1u);
        } else if (p.y <= cover.x) {
            state = LANDED;
            at.y = cover.x;
            atomicAdd(&ground_count[k], 1u);
        } else if (age > snowfall.more.z) {
            state = LEFT;
            atomicAdd(&tally[3], 1u);
        }
    }
    flake_x[i] = vec4<f32>(at, 0.0);
    flake_v[i] = vec4<f32>(vel, state);
}
