//! Poisson-disk filling of a closed mesh (Bridson 2007, "Fast Poisson disk sampling in
//! arbitrary dimensions", SIGGRAPH sketches): points inside the mesh, no two closer than
//! a radius, none of the lattice's regular rows, so a solid filled so has no preferred
//! directions.
//!
//! The algorithm: a background grid of cells `r / sqrt(3)` (at most one point each); an
//! active list; for a random active point, up to [`TRIES`] candidates uniformly in the
//! spherical shell between `r` and `2 r` around it, each kept if it is inside the mesh
//! (the parity of the mesh's crossings along +x, as [`super::fill`] counts them) and no
//! point lies within `r`; a point none of whose candidates is kept leaves the list.
//! Every part of the mesh gets seeds (the lattice points inside at four radii apart), so
//! a mesh of several pieces fills in all of them.
//!
//! The radius is `spacing` times [`RADIUS_PER_SPACING`], so the number of points is about
//! the volume over `spacing^3`, as a lattice fill's is (measured: the tests hold it within
//! 3 %). Random numbers come from SplitMix64 seeded by the caller: the same scene always
//! samples the same points (a generic generator's sequence may change between versions).

use super::TriMesh;
use crate::math::{Real, Vec3};

/// Candidates tried around an active point (Bridson's k).
pub const TRIES: u32 = 30;
/// The disk radius per lattice spacing that gives about one point per `spacing^3`
/// (measured on a torus: Bridson's sampling in 3D packs about 0.61 points per `r^3`).
pub const RADIUS_PER_SPACING: Real = 0.842;

/// SplitMix64 (Steele, Lea & Flood 2014): a small generator with a fixed sequence.
#[derive(Debug, Clone)]
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Which points are inside a closed mesh: the crossings of rows along x, binned by
/// their (y, z) over the mesh's bounds.
struct Inside<'m> {
    mesh: &'m TriMesh,
    min: [f64; 2],
    cell: f64,
    dims: [usize; 2],
    bins: Vec<Vec<u32>>,
}

impl<'m> Inside<'m> {
    fn new(mesh: &'m TriMesh, cell: f64) -> Self {
        let b = mesh.bounds();
        let min = [b.min.y as f64, b.min.z as f64];
        let dims = [
            ((b.max.y - b.min.y) as f64 / cell).ceil() as usize + 1,
            ((b.max.z - b.min.z) as f64 / cell).ceil() as usize + 1,
        ];
        let mut bins = vec![Vec::new(); dims[0] * dims[1]];
        let at = |v: f64, a: usize| (((v - min[a]) / cell).floor().max(0.0) as usize).min(dims[a] - 1);
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| mesh.vertices[i as usize].as_dvec3());
            let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
            for k in at(lo.z, 1)..=at(hi.z, 1) {
                for j in at(lo.y, 0)..=at(hi.y, 0) {
                    bins[k * dims[0] + j].push(t as u32);
                }
            }
        }
        Self { mesh, min, cell, dims, bins }
    }

    /// Whether `p` is inside: two rows through points 1e-4 of a cell apart (along
    /// irrational directions) must agree, so a row that runs along an edge or grazes the
    /// surface, where rounding can miss or double a crossing, rejects the point rather
    /// than misplacing it.
    fn contains(&self, p: Vec3) -> bool {
        let shift = 1e-4 * self.cell;
        self.parity(p, 0.0, 0.0)
            && self.parity(p, shift * (std::f64::consts::SQRT_2 - 1.0), shift * (3f64.sqrt() - 1.0))
    }

    /// The parity of the crossings of the row through `(p.y + dy, p.z + dz)` before `p.x`.
    fn parity(&self, p: Vec3, dy: f64, dz: f64) -> bool {
        let (y, z) = (p.y as f64 + dy, p.z as f64 + dz);
        let j = ((y - self.min[0]) / self.cell).floor();
        let k = ((z - self.min[1]) / self.cell).floor();
        if j < 0.0 || k < 0.0 || j as usize >= self.dims[0] || k as usize >= self.dims[1] {
            return false;
        }
        let bin = &self.bins[k as usize * self.dims[0] + j as usize];
        let before = bin.iter().filter_map(|&t| super::fill::crossing(self.mesh, t, y, z)).filter(|&c| c < p.x as f64);
        before.count() % 2 == 1
    }
}

/// Points inside `mesh`, no two closer than `radius` (m), as Bridson's algorithm places
/// them from `seed`.
pub fn inside(mesh: &TriMesh, radius: Real, seed: u64) -> Vec<Vec3> {
    let b = mesh.bounds();
    let r = radius as f64;
    let cell = r / 3f64.sqrt();
    let dims = [0, 1, 2].map(|a| ((b.max[a] - b.min[a]) as f64 / cell).ceil() as usize + 1);
    let index = |p: Vec3| -> [usize; 3] {
        [0, 1, 2].map(|a| (((p[a] - b.min[a]) as f64 / cell).floor().max(0.0) as usize).min(dims[a] - 1))
    };
    let mut grid: Vec<u32> = vec![u32::MAX; dims[0] * dims[1] * dims[2]];
    let flat = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    let inside_mesh = Inside::new(mesh, r);
    let mut points: Vec<Vec3> = Vec::new();
    let mut active: Vec<u32> = Vec::new();
    let far = |points: &[Vec3], grid: &[u32], p: Vec3| {
        let c = index(p);
        let span = |a: usize| c[a].saturating_sub(2)..=(c[a] + 2).min(dims[a] - 1);
        for k in span(2) {
            for j in span(1) {
                for i in span(0) {
                    let q = grid[flat([i, j, k])];
                    if q != u32::MAX && (points[q as usize] - p).length_squared() < radius * radius {
                        return false;
                    }
                }
            }
        }
        true
    };
    let in_box = |p: Vec3| p.cmpge(b.min).all() && p.cmple(b.max).all();
    let place = |points: &mut Vec<Vec3>, grid: &mut Vec<u32>, active: &mut Vec<u32>, p: Vec3| {
        grid[flat(index(p))] = points.len() as u32;
        active.push(points.len() as u32);
        points.push(p);
    };
    // Seeds in every piece: lattice points inside, four radii apart.
    let seeds = super::fill::inside_lattice(mesh, b, 4.0 * radius);
    let mut rng = SplitMix(seed);
    for s in seeds {
        if far(&points, &grid, s) {
            place(&mut points, &mut grid, &mut active, s);
        }
        while !active.is_empty() {
            let pick = (rng.next() % active.len() as u64) as usize;
            let centre = points[active[pick] as usize];
            let mut kept = false;
            for _ in 0..TRIES {
                // Uniform in the shell [r, 2r]: the radius by the inverse of r^3's
                // distribution, the direction uniform on the sphere.
                let d = (r.powi(3) + rng.unit() * (8.0 - 1.0) * r.powi(3)).cbrt();
                let (cz, phi) = (2.0 * rng.unit() - 1.0, std::f64::consts::TAU * rng.unit());
                let s = (1.0 - cz * cz).sqrt();
                let p = centre + (Vec3::new((s * phi.cos()) as Real, (s * phi.sin()) as Real, cz as Real) * d as Real);
                if in_box(p) && far(&points, &grid, p) && inside_mesh.contains(p) {
                    place(&mut points, &mut grid, &mut active, p);
                    kept = true;
                }
            }
            if !kept {
                active.swap_remove(pick);
            }
        }
    }
    points
}
