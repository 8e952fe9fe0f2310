// The pair weight of the implicit viscosity's diagonal and product kernels
// (floe-engine `viscosity::implicit`, `Pairs::each`):
// w_ij = s m_i m_j (mu_i + mu_j) / (rho_i rho_j) |F_ij|, s the lattice normalisation
// (the `viscosity` uniform's y), F_ij = r dW/dr / (r^2 + 0.01 h^2), at distance r
// (r2 = r^2).

fn pair_weight(m_i: f32, m_j: f32, mu_ij: f32, inv_rho_i: f32, rho_j: f32, r2: f32) -> f32 {
    let eps_h2 = 0.01 * 0.25 * params.support * params.support;
    let r = sqrt(r2);
    let f = -r * kernel_dw_dr(r) / (r2 + eps_h2);
    return m_i * m_j * mu_ij * inv_rho_i / rho_j * f * viscous_walls.y;
}
