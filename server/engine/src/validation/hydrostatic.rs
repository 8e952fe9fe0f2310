//! Hydrostatic column (docs/validation/cases.md case 1; Adami, Hu & Adams 2012, J. Comput.
//! Phys. 231): at rest, `p(y) = rho0 g (H - y)` and `rho = rho0`.

use crate::backend::Particles;

/// Pressure and density error of a settled column.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HydrostaticError {
    /// `||p - p_ref||_2 / ||p_ref||_2` over the column.
    pub pressure_l2: f64,
    /// `max |p - p_ref| / max p_ref`.
    pub pressure_linf: f64,
    /// Mean `|rho - rho0| / rho0` over particles below the surface layer.
    pub mean_density_deviation: f64,
    /// Highest particle centre plus half a spacing (m): the free surface.
    pub surface: f64,
}

/// Compares `p` (with densities and pressures) to the hydrostatic solution of a
/// column of height `h` (m) resting on `y = 0`. Particles within two spacings of
/// the surface are left out of the density mean: summation density is deficient there.
pub fn measure(p: &Particles, rho0: f64, g: f64, h: f64, spacing: f64) -> HydrostaticError {
    let pressures = p.channel("pressure").and_then(|v| v.as_scalars()).expect("pressures requested");
    let densities = p.channel("density").and_then(|v| v.as_scalars()).expect("densities requested");
    let (mut num, mut den, mut worst, mut peak, mut dev, mut count) = (0.0, 0.0, 0.0f64, 0.0f64, 0.0, 0);
    for ((x, &pr), &rho) in p.positions.iter().zip(pressures).zip(densities) {
        let y = x[1] as f64;
        let reference = rho0 * g * (h - y).max(0.0);
        num += (pr as f64 - reference).powi(2);
        den += reference * reference;
        worst = worst.max((pr as f64 - reference).abs());
        peak = peak.max(reference);
        if y < h - 2.0 * spacing {
            dev += (rho as f64 - rho0).abs() / rho0;
            count += 1;
        }
    }
    let surface = p.positions.iter().map(|x| x[1] as f64).fold(f64::NEG_INFINITY, f64::max) + 0.5 * spacing;
    HydrostaticError {
        pressure_l2: (num / den).sqrt(),
        pressure_linf: worst / peak,
        mean_density_deviation: dev / count.max(1) as f64,
        surface,
    }
}
