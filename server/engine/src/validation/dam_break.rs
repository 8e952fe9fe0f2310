//! Dam break surge front against Koshizuka & Oka (1996), Nucl. Sci. Eng. 123,
//! 421-434, and Martin & Moyce (1952), Phil. Trans. R. Soc. A 244, 312-324.
//!
//! Dimensionless time `T = t sqrt(2 g / a)` and front `Z = x_front / a`, with
//! `x_front` the largest fluid particle centre x plus half a spacing, measured
//! from the wall the column rests against (as in the SPlisHSPlasH comparison).

/// The reference data file (`series,T,Z`, `#` comments), embedded.
pub const REFERENCE_CSV: &str = include_str!("../../data/dam_break_surge_front.csv");

/// Name of the Koshizuka & Oka series in [`REFERENCE_CSV`].
pub const KOSHIZUKA_OKA: &str = "koshizuka_oka_1996_experiment";

/// One reference point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrontPoint {
    /// Dimensionless time T.
    pub t: f64,
    /// Dimensionless front position Z.
    pub z: f64,
}

/// The points of `series` in the embedded reference.
pub fn reference(series: &str) -> Vec<FrontPoint> {
    REFERENCE_CSV
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut f = l.split(',');
            (f.next()? == series).then_some(())?;
            Some(FrontPoint { t: f.next()?.parse().ok()?, z: f.next()?.parse().ok()? })
        })
        .collect()
}

/// Front position Z from particle positions: `(max x + spacing/2 - wall_x) / a`.
pub fn front(positions: &[[f32; 3]], wall_x: f64, spacing: f64, a: f64) -> f64 {
    let max_x = positions.iter().map(|p| p[0] as f64).fold(f64::NEG_INFINITY, f64::max);
    (max_x + 0.5 * spacing - wall_x) / a
}

/// Simulated time (s) of dimensionless time `t_dimless`.
pub fn seconds(t_dimless: f64, g: f64, a: f64) -> f64 {
    t_dimless / (2.0 * g / a).sqrt()
}

/// Error of a simulated front history against reference points with `T <= t_max`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FrontError {
    /// Root mean square of `Z_sim - Z_ref` over the points.
    pub rms: f64,
    /// Largest `|Z_sim - Z_ref|`.
    pub max: f64,
    /// Mean of `Z_sim - Z_ref` (positive: the simulated front runs ahead).
    pub bias: f64,
    /// Number of reference points compared.
    pub points: usize,
}

/// Compares `history` (pairs of T and Z, increasing T) with `reference` points
/// with `T <= t_max`, interpolating the history linearly. Points past the end of
/// the history are not compared.
pub fn compare(history: &[(f64, f64)], reference: &[FrontPoint], t_max: f64) -> FrontError {
    let mut diffs = Vec::new();
    for p in reference.iter().filter(|p| p.t <= t_max) {
        let Some(k) = history.windows(2).position(|w| w[0].0 <= p.t && p.t <= w[1].0) else { continue };
        let (a, b) = (history[k], history[k + 1]);
        let s = if b.0 > a.0 { (p.t - a.0) / (b.0 - a.0) } else { 0.0 };
        diffs.push(a.1 + s * (b.1 - a.1) - p.z);
    }
    let n = diffs.len().max(1) as f64;
    FrontError {
        rms: (diffs.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
        max: diffs.iter().map(|d| d.abs()).fold(0.0, f64::max),
        bias: diffs.iter().sum::<f64>() / n,
        points: diffs.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_loads_and_compare_interpolates() {
        let k = reference(KOSHIZUKA_OKA);
        assert_eq!(k.len(), 9);
        assert_eq!(k[0], FrontPoint { t: 0.0, z: 1.0 });
        // A history equal to the reference plus 0.1 has bias 0.1.
        let hist: Vec<(f64, f64)> = k.iter().map(|p| (p.t, p.z + 0.1)).collect();
        let e = compare(&hist, &k, 2.5);
        assert_eq!(e.points, 7);
        assert!((e.bias - 0.1).abs() < 1e-12 && (e.rms - 0.1).abs() < 1e-12 && (e.max - 0.1).abs() < 1e-12);
        assert!((front(&[[0.2, 0.0, 0.0], [0.49, 1.0, 0.0]], 0.0, 0.02, 0.5) - 1.0).abs() < 1e-6);
    }
}
