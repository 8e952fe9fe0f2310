//! Poiseuille flow between plates (docs/validation/cases.md case 3; Morris, Fox & Zhu 1997,
//! J. Comput. Phys. 136, eq. 21): fluid at rest between plates at `y = 0` and
//! `y = L`, periodic along the plates, driven from t = 0 by a body force `F` along x.

use crate::backend::Particles;

/// `v_x(y, t)` of the start-up flow: the steady parabola `F y (L - y) / (2 nu)`
/// less the decaying odd sine modes (terms until they no longer matter in f64).
pub fn velocity(y: f64, t: f64, force: f64, nu: f64, l: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let mut v = force / (2.0 * nu) * y * (l - y);
    for n in 0..200 {
        let k = (2 * n + 1) as f64;
        let term = 4.0 * force * l * l / (nu * pi.powi(3) * k.powi(3))
            * (pi * y * k / l).sin()
            * (-(k * k) * pi * pi * nu * t / (l * l)).exp();
        v -= term;
        if term.abs() < 1e-18 {
            break;
        }
    }
    v
}

/// `||v_x - v_ref||_2 / ||v_ref||_2` over the particles between the plates at time
/// `t`, with the cross-channel velocities counted as error too.
pub fn l2_error(p: &Particles, t: f64, force: f64, nu: f64, l: f64) -> f64 {
    profile_l2_error(p, |y| velocity(y, t, force, nu, l))
}

/// `||v_x - u(y)||_2 / ||u||_2` over the particles for any channel profile `u(y)`,
/// the cross-channel velocities counted as error too.
pub fn profile_l2_error(p: &Particles, reference: impl Fn(f64) -> f64) -> f64 {
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    let (mut num, mut den) = (0.0, 0.0);
    for (x, v) in p.positions.iter().zip(v) {
        let u = reference(f64::from(x[1]));
        let d = [f64::from(v[0]) - u, f64::from(v[1]), f64::from(v[2])];
        num += d.iter().map(|d| d * d).sum::<f64>();
        den += u * u;
    }
    (num / den.max(f64::MIN_POSITIVE)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_at_rest_and_reaches_the_parabola() {
        let (f, nu, l) = (2e-4, 1e-6, 1e-3);
        for y in [0.1e-3, 0.5e-3, 0.9e-3] {
            assert!(velocity(y, 0.0, f, nu, l).abs() < 1e-4 * 1.25e-5, "{y}");
        }
        // The steady peak F L^2 / (8 nu) = 2.5e-5 m/s.
        assert!((velocity(0.5e-3, 10.0, f, nu, l) - 2.5e-5).abs() < 1e-12);
        assert!(velocity(0.5e-3, 0.1, f, nu, l) < velocity(0.5e-3, 0.2, f, nu, l));
    }
}
