// The rheology's viscosity as it is (no temperature shift in the scene).

fn scaled(i: u32, material: u32, mu: f32) -> f32 {
    return mu;
}
