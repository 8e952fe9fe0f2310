//! The lattice points inside a closed mesh: each lattice row along x is crossed
//! with the triangles over its (y, z) (binned on a grid of the rows, so a row
//! tests only the triangles near it), and a point is inside when an odd number
//! of crossings lie before it (the parity rule of ray casting). The rows are
//! shifted by 1e-4 of a spacing off the lattice (by irrational fractions), so a
//! row never runs exactly through a vertex or an edge of a mesh whose vertices sit
//! on round numbers; the points themselves stay on the lattice.

use super::TriMesh;
use crate::math::{Aabb, Real, Vec3};
use rayon::prelude::*;

/// The lattice points of `lattice` (as [`crate::sampling::fill_box`] places them)
/// inside `mesh`, in fill_box's order.
pub fn inside_lattice(mesh: &TriMesh, lattice: Aabb, spacing: Real) -> Vec<Vec3> {
    let [nx, ny, nz] = crate::sampling::lattice_counts(lattice.min.into(), lattice.max.into(), spacing);
    let (nx, ny, nz) = (nx as usize, ny as usize, nz as usize);
    if nx * ny * nz == 0 {
        return Vec::new();
    }
    let shift = (1e-4 * spacing as f64 * (std::f64::consts::SQRT_2 - 1.0), 1e-4 * spacing as f64 * (3f64.sqrt() - 1.0));
    let row_at = |j: usize, k: usize| {
        let y = lattice.min.y as f64 + (j as f64 + 0.5) * spacing as f64 + shift.0;
        let z = lattice.min.z as f64 + (k as f64 + 0.5) * spacing as f64 + shift.1;
        (y, z)
    };
    // Triangles binned by the rows their (y, z) extent covers.
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); ny * nz];
    let cell = |v: f64, min: f32, n: usize| ((v - min as f64) / spacing as f64 - 0.5).clamp(-1.0, n as f64);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| mesh.vertices[i as usize].as_dvec3());
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let j0 = cell(lo.y, lattice.min.y, ny).floor().max(0.0) as usize;
        let j1 = (cell(hi.y, lattice.min.y, ny).ceil() as usize).min(ny.saturating_sub(1));
        let k0 = cell(lo.z, lattice.min.z, nz).floor().max(0.0) as usize;
        let k1 = (cell(hi.z, lattice.min.z, nz).ceil() as usize).min(nz.saturating_sub(1));
        for k in k0..=k1 {
            for j in j0..=j1 {
                bins[k * ny + j].push(t as u32);
            }
        }
    }
    let rows: Vec<Vec<Vec3>> = (0..ny * nz)
        .into_par_iter()
        .map(|r| {
            let (j, k) = (r % ny, r / ny);
            let (y, z) = row_at(j, k);
            let mut crossings: Vec<f64> = bins[r].iter().filter_map(|&t| crossing(mesh, t, y, z)).collect();
            crossings.sort_by(f64::total_cmp);
            let (py, pz) = (lattice.min.y + (j as Real + 0.5) * spacing, lattice.min.z + (k as Real + 0.5) * spacing);
            (0..nx)
                .filter_map(|i| {
                    let x = lattice.min.x + (i as Real + 0.5) * spacing;
                    let before = crossings.partition_point(|&c| c < x as f64);
                    (before % 2 == 1).then(|| Vec3::new(x, py, pz))
                })
                .collect()
        })
        .collect();
    rows.into_iter().flatten().collect()
}

/// Where the row `(y, z)` along x crosses triangle `t`, if it does.
pub(super) fn crossing(mesh: &TriMesh, t: u32, y: f64, z: f64) -> Option<f64> {
    let [a, b, c] = mesh.triangles[t as usize].map(|i| mesh.vertices[i as usize].as_dvec3());
    // Barycentric coordinates of (y, z) in the triangle's projection onto the y-z plane.
    let det = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
    if det == 0.0 {
        return None;
    }
    let u = ((y - a.y) * (c.z - a.z) - (c.y - a.y) * (z - a.z)) / det;
    let v = ((b.y - a.y) * (z - a.z) - (y - a.y) * (b.z - a.z)) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then_some(a.x + u * (b.x - a.x) + v * (c.x - a.x))
}
