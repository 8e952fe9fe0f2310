// The snowfall module's uniform (floe-gpu `modules::snowfall::uniform`) and a
// flake's life (floe-engine `modules::snowfall::flakes`, line for line).

struct Snowfall {
    // The area (the snow grid's): min x, min z, max x, max z (m).
    area: vec4<f32>,
    // Where flakes are born, the same way.
    emit: vec4<f32>,
    // Emission height (m), floor (m), flakes per second, terminal speed (m/s).
    fall: vec4<f32>,
    // Drag's relaxation time (s), mean wind x and z (m/s), gusts.
    air: vec4<f32>,
    // 2 pi / gust period (1/s), flutter (m/s^2), oldest age (s), depth per flake (m).
    more: vec4<f32>,
    // Slots in the ring, cells along x and z, objects.
    sizes: vec4<u32>,
    // The grid's corner x and z (m), cell edge (m), unused.
    grid: vec4<f32>,
    // Turbulence: amplitude (m/s), 1 / scale (1/m), 1 / period (1/s), unused.
    turbulence: vec4<f32>,
    // Two per object: a box (min, 0), (max, 0); a cylinder (cx, bottom, cz, 1), (radius, top, 0, 0).
    objects: array<vec4<f32>, 32>,
}

@group(0) @binding(1) var<uniform> snowfall: Snowfall;

const AIRBORNE: f32 = 1.0;
const LANDED: f32 = 2.0;
const LEFT: f32 = 3.0;
// No object hit.
const NO_TOP: f32 = -3.0e38;

// Chris Wellons' lowbias32.
fn hash(x0: u32) -> u32 {
    var x = x0;
    x = x ^ (x >> 16u);
    x = x * 0x7feb352du;
    x = x ^ (x >> 15u);
    x = x * 0x846ca68bu;
    return x ^ (x >> 16u);
}

fn unit(h: u32) -> f32 {
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

fn over(r: vec4<f32>, p: vec3<f32>) -> bool {
    return p.x >= r.x && p.x <= r.z && p.z >= r.y && p.z <= r.w;
}

fn birth(id: u32) -> vec3<f32> {
    let hx = id * 0xc13fa9a9u;
    let hz = id * 0x91e10da5u;
    let e = snowfall.emit;
    let x = e.x + unit(hx) * (e.z - e.x);
    let z = e.y + unit(hz) * (e.w - e.y);
    return vec3<f32>(x, snowfall.fall.x, z);
}

fn wind(clock: f32) -> vec2<f32> {
    let gust = 1.0 + snowfall.air.w * sin(snowfall.more.x * clock);
    return vec2<f32>(snowfall.air.y * gust, snowfall.air.z * gust);
}

fn flutter(p: vec3<f32>, age: f32) -> vec3<f32> {
    let h0 = hash(bitcast<u32>(p.x) ^ hash(bitcast<u32>(p.z) ^ hash(bitcast<u32>(age))));
    let h1 = hash(h0);
    let h2 = hash(h0 ^ 0x9e3779b9u);
    let f = snowfall.more.y;
    return vec3<f32>(f * (2.0 * unit(h0) - 1.0), f * (2.0 * unit(h1) - 1.0), f * (2.0 * unit(h2) - 1.0));
}

fn cell_of(x: f32, z: f32) -> u32 {
    let g = snowfall.grid;
    let i = u32(clamp(floor((x - g.x) / g.z), 0.0, f32(snowfall.sizes.y - 1u)));
    let k = u32(clamp(floor((z - g.y) / g.z), 0.0, f32(snowfall.sizes.z - 1u)));
    return k * snowfall.sizes.y + i;
}

fn object_top(from_y: f32, p: vec3<f32>, snow: f32) -> f32 {
    for (var o = 0u; o < snowfall.sizes.w; o++) {
        let a = snowfall.objects[2u * o];
        let b = snowfall.objects[2u * o + 1u];
        var over_it: bool;
        if (a.w == 0.0) {
            over_it = p.x >= a.x && p.x <= b.x && p.z >= a.z && p.z <= b.z;
        } else {
            let dx = p.x - a.x;
            let dz = p.z - a.z;
            over_it = dx * dx + dz * dz <= b.x * b.x;
        }
        let top = b.y + snow;
        let inside = p.y >= a.y && p.y <= top;
        let crossed = from_y > top && p.y <= top;
        if (over_it && (inside || crossed)) {
            return top;
        }
    }
    return NO_TOP;
}

// The top, snow included, of a mesh's column over the cell (bottom, top) if the
// flake landed on it (floe-engine `flakes::column_top`), else NO_TOP.
fn column_top(column: vec2<f32>, from_y: f32, y: f32, snow: f32) -> f32 {
    let top = column.y + snow;
    let inside = y >= column.x && y <= top;
    let crossed = from_y > top && y <= top;
    if (column.y >= column.x && (inside || crossed)) {
        return top;
    }
    return NO_TOP;
}

// The turbulence at (x, z) and clock (floe-engine `flakes::turbulence`): value
// noise on a lattice hashed from its integer coordinates, smoothstep-weighted.
fn turbulence(x: f32, z: f32, clock: f32) -> vec2<f32> {
    let t = snowfall.turbulence;
    if (t.x == 0.0) {
        return vec2<f32>(0.0);
    }
    let p = vec3<f32>(x * t.y, z * t.y, clock * t.z);
    let lattice = floor(p);
    let f = p - lattice;
    let s = f * f * (3.0 - 2.0 * f);
    let base = bitcast<vec3<u32>>(vec3<i32>(lattice));
    var out = vec2<f32>(0.0);
    for (var corner = 0u; corner < 8u; corner++) {
        let o = vec3<u32>(corner & 1u, (corner >> 1u) & 1u, (corner >> 2u) & 1u);
        let w = select(1.0 - s, s, o == vec3<u32>(1u));
        let h = hash((base.x + o.x) ^ hash((base.y + o.y) ^ hash(base.z + o.z)));
        out += w.x * w.y * w.z * vec2<f32>(2.0 * unit(h) - 1.0, 2.0 * unit(hash(h)) - 1.0);
    }
    return t.x * out;
}
