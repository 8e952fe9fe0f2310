//! The Taylor-Green vortex (docs/validation/cases.md case 4; Taylor & Green 1937): in a box
//! periodic along x and y with side L, the field `u = -U e^{bt} cos(kx) sin(ky)`,
//! `v = U e^{bt} sin(kx) cos(ky)`, `k = 2 pi / L`, solves the Navier-Stokes
//! equations with `b = -2 k^2 nu = -8 pi^2 nu / L^2`.

use crate::backend::Particles;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The Taylor-Green vortex field in the x-y plane (Taylor & Green 1937; the 2D
/// solution of docs/validation/cases.md §4): `u = -U cos(2 pi x / L) sin(2 pi y / L)`,
/// `v = U sin(2 pi x / L) cos(2 pi y / L)`, x and y from the block's lower corner.
/// It is divergence free and, in a periodic box of side L, decays as `exp(-8 pi^2
/// nu t / L^2)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TaylorGreen {
    /// Peak speed U (m/s).
    pub amplitude: f32,
    /// Wavelength L (m): the side of one period of four vortices.
    pub wavelength: f32,
}

impl TaylorGreen {
    /// `(u, v)` (m/s) at `(x, y)` (m) from the field's origin.
    pub fn velocity(&self, x: f32, y: f32) -> [f32; 2] {
        let k = std::f32::consts::TAU / self.wavelength;
        let (sx, cx) = (k * x).sin_cos();
        let (sy, cy) = (k * y).sin_cos();
        [-self.amplitude * cx * sy, self.amplitude * sx * cy]
    }
}

/// The decay rate b (1/s) of vortices of wavelength `l` (m) at kinematic viscosity `nu` (m^2/s).
pub fn decay_rate(l: f64, nu: f64) -> f64 {
    -8.0 * std::f64::consts::PI.powi(2) * nu / (l * l)
}

/// The particles' root-mean-square speed (m/s); the exact field's is `U e^{bt} / sqrt(2)`.
pub fn rms_speed(p: &Particles) -> f64 {
    let v = velocities(p);
    let sum: f64 = v.iter().map(|v| v.iter().map(|&c| f64::from(c).powi(2)).sum::<f64>()).sum();
    (sum / v.len().max(1) as f64).sqrt()
}

/// The least-squares slope of `ln(speed)` against time over `(t, speed)` samples:
/// the observed decay rate (1/s). `None` with fewer than two usable samples.
pub fn fitted_rate(samples: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = samples.iter().filter(|(_, s)| *s > 0.0).map(|&(t, s)| (t, s.ln())).collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return None;
    }
    let (mt, ms) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sts: f64 = pts.iter().map(|(t, s)| (t - mt) * (s - ms)).sum();
    let stt: f64 = pts.iter().map(|(t, _)| (t - mt).powi(2)).sum();
    (stt > 0.0).then(|| sts / stt)
}

/// The velocity error at time `t` (s) against the exact field of `tg` (origin at
/// the domain's lower corner, `nu` in m^2/s): the mean and the largest magnitude
/// of `v - v_exact` over the particles, both relative to the exact peak `U e^{bt}`.
pub fn velocity_errors(p: &Particles, t: f64, tg: TaylorGreen, nu: f64) -> (f64, f64) {
    let decay = (decay_rate(f64::from(tg.wavelength), nu) * t).exp();
    let peak = f64::from(tg.amplitude) * decay;
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (x, v) in p.positions.iter().zip(velocities(p)) {
        let [u, w] = tg.velocity(x[0], x[1]);
        let d = [f64::from(v[0]) - f64::from(u) * decay, f64::from(v[1]) - f64::from(w) * decay, f64::from(v[2])];
        let e = d.iter().map(|d| d * d).sum::<f64>().sqrt();
        sum += e;
        max = max.max(e);
    }
    (sum / p.positions.len().max(1) as f64 / peak, max / peak)
}

fn velocities(p: &Particles) -> &[[f32; 3]] {
    p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn re_100_decays_at_8_pi_squared_over_100() {
        assert!((decay_rate(1.0, 0.01) + 0.789_568_352).abs() < 1e-8);
        let samples: Vec<(f64, f64)> =
            (0..=20).map(|i| f64::from(i) * 0.1).map(|t| (t, 3.0 * (-0.79 * t).exp())).collect();
        assert!((fitted_rate(&samples).unwrap() + 0.79).abs() < 1e-12);
        assert_eq!(fitted_rate(&samples[..1]), None);
    }

    #[test]
    fn the_preset_starts_on_the_exact_field() {
        let scene = crate::scene::load::from_preset("taylor_green", &["particle_spacing=0.025".into()]).unwrap();
        let sim = crate::Simulation::new_cpu(scene).unwrap();
        let p = sim.read(&["velocity"]);
        let tg = TaylorGreen { amplitude: 1.0, wavelength: 1.0 };
        let (l1, linf) = velocity_errors(&p, 0.0, tg, 0.01);
        assert!(l1 < 1e-6 && linf < 1e-6, "{l1} {linf}");
        assert!((rms_speed(&p) - 0.5f64.sqrt()).abs() < 1e-4, "{}", rms_speed(&p));
    }

    #[test]
    fn the_field_is_the_one_of_validation_md() {
        let tg = TaylorGreen { amplitude: 2.0, wavelength: 1.0 };
        let [u, v] = tg.velocity(0.0, 0.25);
        assert!((u + 2.0).abs() < 1e-6 && v.abs() < 1e-6, "{u} {v}");
        let [u, v] = tg.velocity(0.25, 0.0);
        assert!(u.abs() < 1e-6 && (v - 2.0).abs() < 1e-6, "{u} {v}");
    }
}
