// The WCSPH pressure terms of forces.wgsl: `p / rho^2` per particle
// (wcsph.eos) and the walls' extrapolated pressures (wcsph.wall_pressure).

@group(0) @binding(8) var<storage, read> pterm: array<f32>;
@group(0) @binding(9) var<storage, read> wall_p: array<f32>;

fn pressure_term(i: u32) -> f32 {
    return pterm[i];
}

// `m_j (r_ab p_i/rho_i^2 + r_ba p_j/rho_j^2)`; for equal masses both ratios are 1.
fn pressure_pair(pt_i: f32, j: u32, m_j: f32, r_ab: f32, r_ba: f32) -> f32 {
    return m_j * (pt_i * r_ab + pterm[j] * r_ba);
}

// `psi_b (p_i/rho_i^2 + p_b/rho0^2)`.
fn pressure_wall(pt_i: f32, b: u32, psi: f32, inv_rho0_2: f32) -> f32 {
    return psi * (pt_i + wall_p[b] * inv_rho0_2);
}
