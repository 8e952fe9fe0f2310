// Pressure from density through each material's equation of state, stored as
// `p / rho^2` (floe-engine `schemes::wcsph::cpu::EosPass` and `Eos::pressure`):
// Tait `p = b ((rho/rho0)^gamma - 1)` or linear `p = k (rho - rho0)`, plus the
// background pressure, clamped at 0.

@group(0) @binding(2) var<storage, read> pos: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> rho: array<f32>;
@group(0) @binding(4) var<storage, read_write> pterm: array<f32>;

fn law(e: vec4<f32>, r: f32) -> f32 {
    if (e.x == 0.0) {
        let ratio = r / e.w;
        var p: f32;
        if (e.z == 7.0) {
            let r2 = ratio * ratio;
            p = r2 * r2 * r2 * ratio;
        } else {
            p = pow(ratio, e.z);
        }
        return e.y * (p - 1.0);
    }
    return e.y * (r - e.w);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(gid, groups);
    if (i >= params.n) {
        return;
    }
    let r = rho[i];
    let m = material_of(pos[i]);
    let p = max(law(wcsph.eos[m], r) + wcsph.background[m / 4u][m % 4u], 0.0);
    pterm[i] = p / (r * r);
}
