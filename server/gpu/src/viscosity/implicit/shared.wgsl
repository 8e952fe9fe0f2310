// Shared by the implicit viscosity kernels (floe-engine `viscosity::implicit`).

// a / b, or 0 where b is not positive (a flow at rest).
fn ratio(a: f32, b: f32) -> f32 {
    if (b > 0.0) {
        return a / b;
    }
    return 0.0;
}
