// Temperature-dependent viscosity (floe-engine `modules::heat::viscosity`,
// `TemperatureLaw::viscosity`, term by term): mu = law(T) of the particle's
// material, clamped to [0, max], into the fluid module's per-particle viscosity;
// in scenes with the snow module, the factor law(T) / law(T0) its rheology takes.

@group(0) @binding(1) var<uniform> heat: Heat;
@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> temperature: array<f32>;
// The viscosity `mu` (main) or the shift factor `viscosity_shift` (shift).
@group(0) @binding(4) var<storage, read_write> out: array<f32>;

// Point k of material m's table: (T, mu).
fn table_point(m: u32, k: u32) -> vec2<f32> {
    let v = heat.table[m * 4u + k / 2u];
    if (k % 2u == 0u) {
        return v.xy;
    }
    return v.zw;
}

// The table at t: linear between points, constant beyond the ends.
fn table_at(m: u32, t: f32) -> f32 {
    let n = bitcast<u32>(heat.law_clamp[m].y);
    let first = table_point(m, 0u);
    if (t <= first.x) {
        return first.y;
    }
    for (var k = 1u; k < n; k++) {
        let a = table_point(m, k - 1u);
        let b = table_point(m, k);
        if (t <= b.x) {
            return a.y + (b.y - a.y) * ((t - a.x) / (b.x - a.x));
        }
    }
    return table_point(m, n - 1u).y;
}

// The law of material m at temperature t, clamped to [0, max]; 0 without a law.
fn law_at(m: u32, t: f32) -> f32 {
    let law = heat.law[m];
    var value = 0.0;
    switch bitcast<u32>(law.x) {
        case 1u: { value = law.y * exp(-law.w * (t - law.z)); }
        case 2u: { value = law.y * exp(law.w * (1.0 / t - law.z)); }
        case 3u: { value = table_at(m, t); }
        default: {
            return 0.0;
        }
    }
    return max(min(value, heat.law_clamp[m].x), 0.0);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    out[i] = law_at(material_of(pos[i]), temperature[i]);
}

// The shift factor mu(T) / mu(T0) of the snow module's rheology (`TemperatureLaw::
// shift`): 1 without a law; 1 / mu(T0) in the clamp's z.
@compute @workgroup_size(WG)
fn shift(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let m = material_of(pos[i]);
    if (bitcast<u32>(heat.law[m].x) == 0u) {
        out[i] = 1.0;
        return;
    }
    out[i] = law_at(m, temperature[i]) * heat.law_clamp[m].z;
}
