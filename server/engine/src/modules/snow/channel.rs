//! Reference velocity profiles of the channel flows (docs/validation/cases.md §6): plates at
//! `y = 0` and `y = L`, a body force F along them, steady state. With `s` the
//! distance from the centre line and `H = L / 2`, the shear stress is `rho F s`
//! whatever the fluid (force balance), so:
//!
//! - power law: `u = n/(n+1) (rho F / K)^(1/n) (H^((n+1)/n) - s^((n+1)/n))`;
//! - Bingham: an unsheared plug for `s <= y0 = tau_0 / (rho F)`, outside it
//!   `u = rho F / (2 mu_p) ((H - y0)^2 - (s - y0)^2)`;
//! - any law (the Cross model has no closed form): the same ODE solved on a 1D
//!   grid, [`steady_profile`]: at each node the shear rate g with `mu(g) g = rho F s`
//!   (bisection; the stress grows with g for every law here), then `u` by the
//!   trapezoidal rule from the wall.

use super::rheology::Law;
use crate::backend::Particles;

/// The power-law profile at `y` (m).
pub fn power_law(y: f64, rho_f: f64, k: f64, n: f64, l: f64) -> f64 {
    let (h, s) = (0.5 * l, (y - 0.5 * l).abs().min(0.5 * l));
    let e = (n + 1.0) / n;
    n / (n + 1.0) * (rho_f / k).powf(1.0 / n) * (h.powf(e) - s.powf(e))
}

/// The Bingham profile at `y` (m).
pub fn bingham(y: f64, rho_f: f64, tau0: f64, mu_p: f64, l: f64) -> f64 {
    let (h, s) = (0.5 * l, (y - 0.5 * l).abs().min(0.5 * l));
    let y0 = (tau0 / rho_f).min(h);
    let sheared = (s - y0).max(0.0);
    rho_f / (2.0 * mu_p) * ((h - y0).powi(2) - sheared * sheared)
}

/// A profile on a grid from the wall (`y = 0`) to the centre line; symmetric.
#[derive(Debug, Clone)]
pub struct Profile {
    /// Node spacing (m).
    dy: f64,
    /// Velocities (m/s) at `y = k dy`, up to the centre line.
    u: Vec<f64>,
}

impl Profile {
    /// The velocity at `y` (m), linearly interpolated.
    pub fn at(&self, y: f64) -> f64 {
        let l = 2.0 * self.dy * (self.u.len() - 1) as f64;
        let y = y.clamp(0.0, l);
        let y = if y > 0.5 * l { l - y } else { y };
        let f = y / self.dy;
        let k = (f.floor() as usize).min(self.u.len() - 2);
        let t = f - k as f64;
        self.u[k] * (1.0 - t) + self.u[k + 1] * t
    }
}

/// The shear rate (1/s) at which `law` carries the stress `tau` (Pa).
fn shear_rate_for(law: &Law, tau: f64) -> f64 {
    let stress = |g: f64| f64::from(law.viscosity(g as f32)) * g;
    let mut hi = 1e-6;
    while stress(hi) < tau && hi < 1e12 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if stress(mid) < tau { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// The steady profile of `law` between plates `l` (m) apart, driven by `rho_f`
/// (rho F, Pa/m), on `cells` grid cells across half the channel.
pub fn steady_profile(law: &Law, rho_f: f64, l: f64, cells: usize) -> Profile {
    let h = 0.5 * l;
    let dy = h / cells as f64;
    let g: Vec<f64> = (0..=cells).map(|k| shear_rate_for(law, rho_f * (h - k as f64 * dy))).collect();
    let mut u = vec![0.0; cells + 1];
    for k in 1..=cells {
        u[k] = u[k - 1] + 0.5 * dy * (g[k - 1] + g[k]);
    }
    Profile { dy, u }
}

pub use crate::validation::poiseuille::profile_l2_error as l2_error;

/// Mean velocity along the channel (m/s) of each lattice layer `y = (k + 1/2) d`.
pub fn layers(p: &Particles, spacing: f64, l: f64) -> Vec<f64> {
    let v = p.channel("velocity").and_then(|v| v.as_vectors()).expect("velocities requested");
    let count = (l / spacing).round() as usize;
    let (mut sum, mut n) = (vec![0.0; count], vec![0usize; count]);
    for (x, v) in p.positions.iter().zip(v) {
        let k = (f64::from(x[1]) / spacing - 0.5).round().clamp(0.0, (count - 1) as f64) as usize;
        sum[k] += f64::from(v[0]);
        n[k] += 1;
    }
    sum.iter().zip(&n).map(|(s, &n)| s / n.max(1) as f64).collect()
}

/// Half-width (m) of the plug of layer velocities `u` (spacing `d`, channel `l`):
/// the distance from the centre line to where the shear rate between layers first
/// reaches a tenth of its largest value, interpolated between layer midpoints.
pub fn plug_half_width(u: &[f64], d: f64, l: f64) -> f64 {
    let rates: Vec<(f64, f64)> = u
        .windows(2)
        .enumerate()
        .map(|(k, w)| (((k + 1) as f64 * d - 0.5 * l).abs(), ((w[1] - w[0]) / d).abs()))
        .collect();
    let threshold = 0.1 * rates.iter().map(|r| r.1).fold(0.0, f64::max);
    let mut by_distance = rates;
    by_distance.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut previous = (0.0, 0.0);
    for (s, g) in by_distance {
        if g >= threshold {
            let t = if g > previous.1 { (threshold - previous.1) / (g - previous.1) } else { 1.0 };
            return previous.0 + t.clamp(0.0, 1.0) * (s - previous.0);
        }
        previous = (s, g);
    }
    0.5 * l
}

#[cfg(test)]
mod tests {
    use super::super::spec::Rheology;
    use super::*;

    #[test]
    fn the_grid_solution_converges_to_the_closed_forms() {
        let (rho_f, l) = (100.0, 1.0);
        let power = Law::new(&Rheology::PowerLaw { k: 4472.0, n: 1.5 }, 1e9);
        let newtonian = Law::new(&Rheology::Newtonian { mu: 1000.0 }, 1e9);
        for y in [0.05, 0.2, 0.5, 0.8] {
            let p = steady_profile(&power, rho_f, l, 400).at(y);
            let exact = power_law(y, rho_f, 4472.0, 1.5, l);
            assert!((p - exact).abs() < 1e-3 * exact, "{y}: {p} vs {exact}");
            // A Newtonian fluid: the parabola F y (L - y) / (2 nu).
            let n = steady_profile(&newtonian, rho_f, l, 400).at(y);
            assert!((n - 0.05 * y * (l - y)).abs() < 1e-4 * n, "{y}: {n}");
        }
        // A Bingham plastic with a large regularisation approaches the ideal plug.
        let b = Law::new(&Rheology::Bingham { yield_stress: 15.0, mu_p: 1000.0, m: 1e5 }, 1e9);
        for y in [0.1, 0.3, 0.5] {
            let p = steady_profile(&b, rho_f, l, 2000).at(y);
            let exact = bingham(y, rho_f, 15.0, 1000.0, l);
            assert!((p - exact).abs() < 2e-3 * exact, "{y}: {p} vs {exact}");
        }
    }

    #[test]
    fn the_plug_width_of_the_bingham_profile() {
        let (d, l) = (0.01, 1.0);
        let u: Vec<f64> = (0..100).map(|k| bingham((k as f64 + 0.5) * d, 100.0, 15.0, 1000.0, l)).collect();
        // The shear rate is rho F (s - y0) / mu_p: a tenth of the wall's at
        // s = y0 + 0.1 (H - y0) = 0.185 m.
        let w = plug_half_width(&u, d, l);
        assert!((w - 0.185).abs() < 0.01, "{w}");
    }
}
