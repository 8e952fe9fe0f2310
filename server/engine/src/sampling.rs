//! Turning scene geometry into particles: boxes on a cubic lattice, and walls as
//! layers of boundary particles (Akinci et al. 2012, section 3).

use crate::math::{Real, Vec3};
use crate::scene::{Boundary, Face};
use crate::terrain::HeightGrid;

/// Particles along each axis of the box `min`-`max` on a lattice of `spacing`.
pub(crate) fn lattice_counts(min: [f32; 3], max: [f32; 3], spacing: Real) -> [u32; 3] {
    let counts = ((Vec3::from(max) - Vec3::from(min)) / spacing + 1e-3).floor();
    [counts.x as u32, counts.y as u32, counts.z as u32]
}

/// How many particles [`fill_box`] places in the box `min`-`max`, counted without
/// placing them (a server refuses a scene too large before it is built).
pub fn box_count(min: [f32; 3], max: [f32; 3], spacing: Real) -> u64 {
    lattice_counts(min, max, spacing).iter().fold(1u64, |n, &c| n.saturating_mul(u64::from(c)))
}

/// Particle centres filling the box `min`-`max` on a lattice of `spacing`, the
/// first one half a spacing inside the lower corner.
pub fn fill_box(min: [f32; 3], max: [f32; 3], spacing: Real) -> Vec<Vec3> {
    let [nx, ny, nz] = lattice_counts(min, max, spacing);
    let min = Vec3::from(min);
    let mut out = Vec::with_capacity((nx * ny * nz) as usize);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                out.push(min + (Vec3::new(i as Real, j as Real, k as Real) + 0.5) * spacing);
            }
        }
    }
    out
}

/// Lattice coordinates along one axis of a box: `layers` outside below, the
/// interior (spacing stretched to fit the extent exactly), `layers` outside above.
/// Returns the coordinates and, for each, -1 / 0 / +1 for below / inside / above.
///
/// Where the extent is not a whole number of spacings, a wall beside a column of
/// fluid drifts against the fluid's layers (docs/validation/schemes/CG.md, "The
/// tank's walls"). Keeping the fluid's lattice from `lo` instead, the remainder left
/// at the far face, was measured and not kept: the resting column came right, but the
/// dam break's front, whose walls became level with its layers, ran further ahead of
/// the experiment (front RMS 0.228 -> 0.237 at 21,952 particles). An extent that is
/// a whole number of spacings to rounding keeps the spacing itself: `1.05 / 21` is not
/// `0.05` in single precision, and walls 1e-7 m off the fluid's lattice set a WCSPH
/// column on another course.
fn axis_coords(lo: Real, hi: Real, spacing: Real, layers: u32) -> Vec<(Real, i8)> {
    let cells = (hi - lo) / spacing;
    let n = cells.round().max(1.0) as u32;
    let d = if (cells - n as Real).abs() < 1e-4 { spacing } else { (hi - lo) / n as Real };
    let mut out = Vec::new();
    for l in (0..layers).rev() {
        out.push((lo - (l as Real + 0.5) * d, -1));
    }
    for i in 0..n {
        out.push((lo + (i as Real + 0.5) * d, 0));
    }
    for l in 0..layers {
        out.push((hi + (l as Real + 0.5) * d, 1));
    }
    out
}

/// Boundary particle positions for one wall. Along the axes flagged in `periodic`
/// a box has no faces: its walls tile the period with no layers beyond it. A terrain
/// is sampled from its rasterised heights (`grid`, `None` for the other walls).
pub fn sample_boundary(
    boundary: &Boundary,
    spacing: Real,
    periodic: [bool; 3],
    grid: Option<&HeightGrid>,
) -> Vec<Vec3> {
    match boundary {
        Boundary::Box { min, max, open, layers } => {
            let axes: Vec<Vec<(Real, i8)>> =
                (0..3).map(|a| axis_coords(min[a], max[a], spacing, if periodic[a] { 0 } else { *layers })).collect();
            let is_open = |axis: usize, side: i8| {
                open.iter().any(|f| {
                    matches!(
                        (f, axis, side),
                        (Face::MinusX, 0, -1)
                            | (Face::PlusX, 0, 1)
                            | (Face::MinusY, 1, -1)
                            | (Face::PlusY, 1, 1)
                            | (Face::MinusZ, 2, -1)
                            | (Face::PlusZ, 2, 1)
                    )
                })
            };
            let mut out = Vec::new();
            for &(z, sz) in &axes[2] {
                for &(y, sy) in &axes[1] {
                    for &(x, sx) in &axes[0] {
                        let sides = [sx, sy, sz];
                        let in_shell = sides.iter().any(|&s| s != 0);
                        let on_open = sides.iter().enumerate().any(|(a, &s)| s != 0 && is_open(a, s));
                        if in_shell && !on_open {
                            out.push(Vec3::new(x, y, z));
                        }
                    }
                }
            }
            out
        }
        Boundary::Plane { center, normal, size, layers } => {
            let n = Vec3::from(*normal).normalize();
            let t1 = n.any_orthonormal_vector();
            let t2 = n.cross(t1);
            let (nu, nv) = ((size[0] / spacing).round().max(1.0) as u32, (size[1] / spacing).round().max(1.0) as u32);
            let (du, dv) = (size[0] / nu as Real, size[1] / nv as Real);
            let c = Vec3::from(*center);
            let mut out = Vec::new();
            for l in 0..*layers {
                for j in 0..nv {
                    for i in 0..nu {
                        let u = (i as Real + 0.5) * du - 0.5 * size[0];
                        let v = (j as Real + 0.5) * dv - 0.5 * size[1];
                        out.push(c + t1 * u + t2 * v - n * ((l as Real + 0.5) * spacing));
                    }
                }
            }
            out
        }
        Boundary::Terrain(t) => {
            crate::terrain::sample_surface(grid.expect("a terrain is sampled from its height grid"), spacing, t.layers)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_fill_on_the_lattice() {
        let p = fill_box([0.0; 3], [1.0, 2.0, 0.5], 0.1);
        assert_eq!(p.len(), 10 * 20 * 5);
        assert_eq!(box_count([0.0; 3], [1.0, 2.0, 0.5], 0.1), 1000);
        assert!((p[0] - Vec3::splat(0.05)).length() < 1e-6);
    }

    #[test]
    fn box_walls_form_a_closed_shell() {
        let b = Boundary::Box { min: [0.0; 3], max: [1.0; 3], open: vec![], layers: 1 };
        let p = sample_boundary(&b, 0.1, [false; 3], None);
        assert_eq!(p.len(), 12 * 12 * 12 - 10 * 10 * 10);
        assert!(p.iter().all(|q| q.min_element() < 0.0 || q.max_element() > 1.0));
        let open = Boundary::Box { min: [0.0; 3], max: [1.0; 3], open: vec![Face::PlusY], layers: 2 };
        let p = sample_boundary(&open, 0.1, [false; 3], None);
        assert!(p.iter().all(|q| q.y < 1.0));
        assert_eq!(p.len(), 14 * 12 * 14 - 10 * 10 * 10);
        // Periodic along x: two plates (y faces) and two side walls (z faces), no x faces,
        // nothing beyond the period.
        let channel = Boundary::Box { min: [0.0; 3], max: [1.0; 3], open: vec![Face::MinusX, Face::PlusX], layers: 2 };
        let p = sample_boundary(&channel, 0.1, [true, false, false], None);
        assert_eq!(p.len(), 10 * (14 * 14 - 10 * 10));
        assert!(p.iter().all(|q| (0.0..1.0).contains(&q.x)));
    }

    #[test]
    fn whole_extents_keep_the_fluids_lattice_bit_for_bit() {
        // 1.05 / 21 is not 0.05 in single precision: the walls take the spacing itself.
        let b = Boundary::Box { min: [0.0; 3], max: [0.3, 1.05, 0.15], open: vec![], layers: 1 };
        let side: Vec<f32> =
            sample_boundary(&b, 0.05, [false; 3], None).into_iter().filter(|q| q.x < 0.0).map(|q| q.y).collect();
        for y in fill_box([0.0; 3], [0.3, 0.9, 0.15], 0.05).iter().map(|q| q.y) {
            assert!(side.contains(&y), "no wall particle exactly level with the layer at {y}");
        }
    }

    #[test]
    fn planes_sit_behind_their_normal() {
        let b = Boundary::Plane { center: [0.0; 3], normal: [0.0, 2.0, 0.0], size: [1.0, 0.5], layers: 2 };
        let p = sample_boundary(&b, 0.1, [false; 3], None);
        assert_eq!(p.len(), 2 * 10 * 5);
        assert!(p.iter().all(|q| q.y < 0.0 && q.y > -0.2));
    }
}
