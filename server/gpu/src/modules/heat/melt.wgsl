// The integration where a fluid melts (floe-engine `modules::heat::phase::Melt`):
// particles that never change phase integrate their temperature; those that melt
// or freeze their enthalpy H += c dT/dt dt, from which their temperature, liquid
// fraction and phase follow (the material index in the w of x).

@group(0) @binding(1) var<uniform> dt: vec4<f32>;
@group(0) @binding(2) var<uniform> heat: Heat;
@group(0) @binding(3) var<storage, read_write> pos: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> temperature: array<f32>;
@group(0) @binding(5) var<storage, read_write> temperature_carry: array<f32>;
@group(0) @binding(6) var<storage, read> heat_rate: array<f32>;
@group(0) @binding(7) var<storage, read_write> enthalpy: array<f32>;
@group(0) @binding(8) var<storage, read_write> enthalpy_carry: array<f32>;
@group(0) @binding(9) var<storage, read_write> liquid_fraction: array<f32>;

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let m = material_of(pos[i]);
    let change = heat.phase_of[m];
    if (change.z == 0u) {
        let s = compensated_add(temperature[i], temperature_carry[i], dt.x * heat_rate[i], dt.w);
        temperature[i] = s.x;
        temperature_carry[i] = s.y;
        return;
    }
    // Melting point, latent heat, the solid's and the melt's capacities.
    let p = heat.phase[m];
    let s = compensated_add(enthalpy[i], enthalpy_carry[i], dt.x * heat_rate[i] * heat.material[m].y, dt.w);
    let h = s.x;
    enthalpy[i] = h;
    enthalpy_carry[i] = s.y;
    var t = p.x;
    if (h < 0.0) {
        t = p.x + h / p.z;
    } else if (h > p.y) {
        t = p.x + (h - p.y) / p.w;
    }
    temperature[i] = t;
    liquid_fraction[i] = clamp(h / p.y, 0.0, 1.0);
    var own = m;
    if (h >= p.y) {
        own = change.y;
    } else if (h <= 0.0) {
        own = change.x;
    }
    pos[i].w = f32(own);
}
