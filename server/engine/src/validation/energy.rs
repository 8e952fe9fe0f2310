//! Mechanical energy of the fluid: kinetic plus gravitational potential,
//! `E = sum_i m (|v_i|^2 / 2 - g . x_i)` (J). Weakly compressible SPH also stores
//! a small elastic energy in compression, left out here; dissipation makes E
//! fall, so E rising well above its start is the signature of an instability.

use crate::backend::Particles;

/// Mechanical energy (J) of particles of mass `mass` (kg) under gravity `g` (m/s^2).
pub fn mechanical(p: &Particles, mass: f64, g: [f32; 3]) -> f64 {
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    p.positions
        .iter()
        .zip(v)
        .map(|(x, v)| {
            let kinetic = 0.5 * (v[0] as f64).powi(2) + 0.5 * (v[1] as f64).powi(2) + 0.5 * (v[2] as f64).powi(2);
            let potential = -(g[0] as f64 * x[0] as f64 + g[1] as f64 * x[1] as f64 + g[2] as f64 * x[2] as f64);
            mass * (kinetic + potential)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_of_a_falling_pair() {
        let p = Particles {
            positions: vec![[0.0, 2.0, 0.0], [1.0, 0.0, 0.0]],
            channels: vec![("velocity".into(), floe_proto::Values::vectors(vec![[0.0, -3.0, 0.0], [4.0, 0.0, 0.0]]))],
            ..Default::default()
        };
        // m (9/2 + 9.81*2) + m (16/2)
        let e = mechanical(&p, 2.0, [0.0, -9.81, 0.0]);
        assert!((e - 2.0 * (4.5 + 19.62 + 8.0)).abs() < 1e-4, "{e}");
    }
}
