// What the stability guard and the time step need, reduced over all particles
// (floe-engine `cpu::core::measure` and `Measures::merge`): largest squared
// speed and acceleration, largest compression against each particle's own
// material, the compression sum, and the first non-finite and first
// out-of-domain particle. `partials` reduces each
// workgroup; `total` reduces the partials in one workgroup. Ties keep the lower
// slot, as on the CPU.

struct Measures {
    speed2: f32,
    speed_slot: u32,
    accel2: f32,
    compression: f32,
    compression_slot: u32,
    compression_sum: f32,
    non_finite: u32,
    outside: u32,
}

const RW: u32 = 256u;
const NO_SLOT: u32 = 0xffffffffu;

@group(0) @binding(1) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> vel: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> acc: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> rho_of: array<f32>;
@group(0) @binding(5) var<storage, read_write> parts: array<Measures>;

var<workgroup> shared_m: array<Measures, RW>;

fn empty() -> Measures {
    return Measures(0.0, 0u, 0.0, 0.0, 0u, 0.0, NO_SLOT, NO_SLOT);
}

fn merge(a: Measures, b: Measures) -> Measures {
    var m = a;
    if (b.speed2 > a.speed2) {
        m.speed2 = b.speed2;
        m.speed_slot = b.speed_slot;
    }
    m.accel2 = max(a.accel2, b.accel2);
    if (b.compression > a.compression) {
        m.compression = b.compression;
        m.compression_slot = b.compression_slot;
    }
    m.compression_sum = a.compression_sum + b.compression_sum;
    m.non_finite = min(a.non_finite, b.non_finite);
    m.outside = min(a.outside, b.outside);
    return m;
}

fn of_particle(i: u32) -> Measures {
    var m = empty();
    let x = pos[i].xyz;
    let v = vel[i].xyz;
    let a = acc[i].xyz;
    let rho = rho_of[i];
    if (any(vec4<bool>(non_finite(x.x), non_finite(x.y), non_finite(x.z), non_finite(rho)))
        || any(vec3<bool>(non_finite(v.x), non_finite(v.y), non_finite(v.z)))
        || any(vec3<bool>(non_finite(a.x), non_finite(a.y), non_finite(a.z)))) {
        m.non_finite = i;
        return m;
    }
    let s2 = dot(v, v);
    if (s2 > 0.0) {
        m.speed2 = s2;
        m.speed_slot = i;
    }
    m.accel2 = dot(a, a);
    let rho0 = params.materials[material_of(pos[i])].x;
    let c = (rho - rho0) / rho0;
    if (c > 0.0) {
        m.compression = c;
        m.compression_slot = i;
    }
    m.compression_sum = max(c, 0.0);
    if (any(x < params.domain_min) || any(x > params.domain_max)) {
        m.outside = i;
    }
    return m;
}

// Tree reduction of `shared_m`; the result lands in `shared_m[0]`.
fn reduce_workgroup(t: u32) {
    for (var stride = RW / 2u; stride > 0u; stride >>= 1u) {
        workgroupBarrier();
        if (t < stride) {
            shared_m[t] = merge(shared_m[t], shared_m[t + stride]);
        }
    }
    workgroupBarrier();
}

@compute @workgroup_size(RW)
fn partials(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let w = wid.x + wid.y * groups.x;
    let i = w * RW + lid.x;
    var m = empty();
    if (i < params.n) {
        m = of_particle(i);
    }
    shared_m[lid.x] = m;
    reduce_workgroup(lid.x);
    if (lid.x == 0u && w * RW < params.n) {
        parts[w] = shared_m[0];
    }
}

// `parts[0]` becomes the total of `parts[0..count]`, count = ceil(n / 256).
@compute @workgroup_size(RW)
fn total(@builtin(local_invocation_id) lid: vec3<u32>) {
    let count = (params.n + RW - 1u) / RW;
    var m = empty();
    for (var k = lid.x; k < count; k += RW) {
        m = merge(m, parts[k]);
    }
    shared_m[lid.x] = m;
    reduce_workgroup(lid.x);
    if (lid.x == 0u) {
        parts[0] = shared_m[0];
    }
}
