// No pressure terms in forces.wgsl: the scheme solves pressure on its own.

fn pressure_term(i: u32) -> f32 {
    return 0.0;
}

fn pressure_pair(pt_i: f32, j: u32, m_j: f32, r_ab: f32, r_ba: f32) -> f32 {
    return 0.0;
}

fn pressure_wall(pt_i: f32, b: u32, psi: f32, inv_rho0_2: f32) -> f32 {
    return 0.0;
}
