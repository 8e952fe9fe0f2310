// The rheology's viscosity times the heat module's temperature shift factor,
// clamped again to the material's largest viscosity (floe-engine
// `modules::snow::shear`, `SHEAR_SHIFTED`).

@group(0) @binding(9) var<storage, read> viscosity_shift: array<f32>;

fn scaled(i: u32, material: u32, mu: f32) -> f32 {
    return min(viscosity_shift[i] * mu, snow.kind[material].y);
}
