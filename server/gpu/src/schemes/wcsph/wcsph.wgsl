// The WCSPH scheme's uniform (floe-engine `schemes::wcsph::WcsphConsts`), shared
// by its kernels.

struct Wcsph {
    // Per material: kind (0 Tait, 1 linear), b or k, gamma, rho0.
    eos: array<vec4<f32>, 16>,
    // Per material: the equation of state's background pressure (Pa), four to a vector.
    background: array<vec4<f32>, 4>,
    // x: the transport velocity's background pressure p_b (Pa), 0 without one.
    transport: vec4<f32>,
    // δ-SPH: x eta^2 = 0.01 h^2 (m^2).
    delta: vec4<f32>,
    // δ-SPH, per material: rho0 g / c^2 (kg/m^4) in xyz, the diffusion's coefficient
    // 2 delta h c (m^2/s, c the material's own speed of sound) in w.
    delta_material: array<vec4<f32>, 16>,
}

@group(0) @binding(1) var<uniform> wcsph: Wcsph;
