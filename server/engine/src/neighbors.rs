//! Uniform-grid neighbour search with a counting sort (O(N) per rebuild).
//!
//! The cell edge equals the kernel support, so every neighbour of a particle lies
//! in the 3x3x3 block of cells around it. Cells are numbered x-fastest, and
//! particles are reordered by cell, so the three cells of a block that share
//! (y, z) are one contiguous run of particles: a query visits 9 runs, not 27
//! cells, and neighbouring particles sit next to each other in memory.
//!
//! Positions outside the grid are clamped into its border cells; the stability
//! guard halts a scene whose particles leave the domain, so clamping only has to
//! keep the search memory-safe, not exact.
//!
//! On a periodic axis (see [`crate::periodic`]) the cells tile the period exactly
//! (as many as fit, each at least the support wide) and the block wraps around: the
//! cells below cell 0 are the last ones. A block that wraps along x is two runs
//! instead of one; a period of fewer than three cells visits each cell once.

use crate::math::{Aabb, Real, Vec3};
use std::ops::Range;

/// Grid geometry plus the particle ranges of each cell after the last [`Grid::sort`].
#[derive(Debug, Clone)]
pub struct Grid {
    origin: Vec3,
    inv_cell: Vec3,
    dims: [u32; 3],
    wrap: [bool; 3],
    /// `starts[c]..starts[c + 1]` are the sorted indices of the particles in cell `c`.
    starts: Vec<u32>,
}

impl Grid {
    /// A grid of cells at least `cell` (m) wide covering `bounds`, wrapping around on
    /// the axes flagged in `wrap` (cubic cells of edge `cell` on the others).
    pub fn new(bounds: Aabb, cell: Real, wrap: [bool; 3]) -> Self {
        let size = bounds.size();
        let mut dims = [1u32; 3];
        let mut inv_cell = Vec3::splat(1.0 / cell);
        for a in 0..3 {
            if wrap[a] {
                dims[a] = ((size[a] / cell).floor() as u32).max(1);
                inv_cell[a] = dims[a] as Real / size[a];
            } else {
                dims[a] = ((size[a] / cell).ceil() as u32).max(1);
            }
        }
        let cells = dims.iter().map(|&d| d as usize).product::<usize>();
        Self { origin: bounds.min, inv_cell, dims, wrap, starts: vec![0; cells + 1] }
    }

    /// Lower corner of cell (0, 0, 0) (m).
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Inverse cell edge per axis (1/m).
    pub fn inv_cell(&self) -> Vec3 {
        self.inv_cell
    }

    /// Cells per axis.
    pub fn dims(&self) -> [u32; 3] {
        self.dims
    }

    /// Whether each axis wraps around.
    pub fn wraps(&self) -> [bool; 3] {
        self.wrap
    }

    /// Cell run starts after the last sort (`cell_count + 1` entries).
    pub fn starts(&self) -> &[u32] {
        &self.starts
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.starts.len() - 1
    }

    #[inline(always)]
    fn coords(&self, p: Vec3) -> [u32; 3] {
        let c = (p - self.origin) * self.inv_cell;
        let clamp = |v: Real, d: u32| (v.max(0.0) as u32).min(d - 1);
        [clamp(c.x, self.dims[0]), clamp(c.y, self.dims[1]), clamp(c.z, self.dims[2])]
    }

    /// Linear index of the cell holding `p` (x fastest).
    #[inline(always)]
    pub fn cell_of(&self, p: Vec3) -> u32 {
        let [x, y, z] = self.coords(p);
        x + self.dims[0] * (y + self.dims[1] * z)
    }

    /// Counting sort of `positions` by cell. Returns the permutation `order`
    /// (`order[k]` is the old index of the particle that goes to slot `k`).
    /// `cells` is scratch space, resized as needed.
    pub fn sort(&mut self, positions: &[Vec3], cells: &mut Vec<u32>, order: &mut Vec<u32>) {
        use rayon::prelude::*;
        cells.resize(positions.len(), 0);
        cells
            .par_iter_mut()
            .with_min_len(4096)
            .zip(positions.par_iter().with_min_len(4096))
            .for_each(|(c, &p)| *c = self.cell_of(p));
        self.starts.fill(0);
        for &c in cells.iter() {
            self.starts[c as usize + 1] += 1;
        }
        for c in 0..self.cell_count() {
            self.starts[c + 1] += self.starts[c];
        }
        order.resize(positions.len(), 0);
        // Scatter, using `starts[c]` as the running cursor of cell c, then shift
        // the cursors back so `starts` holds the run starts again.
        for (i, &c) in cells.iter().enumerate() {
            let slot = &mut self.starts[c as usize];
            order[*slot as usize] = i as u32;
            *slot += 1;
        }
        for c in (1..=self.cell_count()).rev() {
            self.starts[c] = self.starts[c - 1];
        }
        self.starts[0] = 0;
    }

    /// Calls `f` with each run of sorted particle indices that may hold a
    /// neighbour of `p` (9 contiguous runs at most, 18 where the block wraps along x).
    #[inline(always)]
    pub fn for_each_run(&self, p: Vec3, mut f: impl FnMut(Range<usize>)) {
        let [x, y, z] = self.coords(p);
        let [dx, dy, dz] = self.dims;
        if self.wrap == [false; 3] {
            let x0 = x.saturating_sub(1);
            let x1 = (x + 1).min(dx - 1);
            for zz in z.saturating_sub(1)..=(z + 1).min(dz - 1) {
                for yy in y.saturating_sub(1)..=(y + 1).min(dy - 1) {
                    self.visit(dx * (yy + dy * zz), x0, x1, &mut f);
                }
            }
            return;
        }
        let (xs, nx) = self.x_runs(x);
        let (ys, ny) = self.block_axis(1, y);
        let (zs, nz) = self.block_axis(2, z);
        for &zz in &zs[..nz] {
            for &yy in &ys[..ny] {
                let row = dx * (yy + dy * zz);
                for &(x0, x1) in &xs[..nx] {
                    self.visit(row, x0, x1, &mut f);
                }
            }
        }
    }

    /// Calls `f` with the particles of cells `x0..=x1` of the row starting at cell `row`.
    #[inline(always)]
    fn visit(&self, row: u32, x0: u32, x1: u32, f: &mut impl FnMut(Range<usize>)) {
        let start = self.starts[(row + x0) as usize] as usize;
        let end = self.starts[(row + x1 + 1) as usize] as usize;
        if start < end {
            f(start..end);
        }
    }

    /// The distinct cells of the block along axis `a` around cell `c` (wrapped on a
    /// periodic axis, clamped on an open one), and how many there are.
    #[inline(always)]
    fn block_axis(&self, a: usize, c: u32) -> ([u32; 3], usize) {
        let d = self.dims[a];
        if !self.wrap[a] {
            let (lo, hi) = (c.saturating_sub(1), (c + 1).min(d - 1));
            return ([lo, lo + 1, hi], (hi - lo + 1) as usize);
        }
        if d < 3 {
            return ([0, 1, 0], d as usize);
        }
        ([(c + d - 1) % d, c, (c + 1) % d], 3)
    }

    /// The block along x around cell `x` as ranges of contiguous cells (two where it
    /// wraps around), and how many there are.
    #[inline(always)]
    fn x_runs(&self, x: u32) -> ([(u32, u32); 2], usize) {
        let d = self.dims[0];
        let lo = x.saturating_sub(1);
        let hi = (x + 1).min(d - 1);
        if !self.wrap[0] || d < 3 {
            let (lo, hi) = if self.wrap[0] { (0, d - 1) } else { (lo, hi) };
            return ([(lo, hi), (0, 0)], 1);
        }
        match x {
            0 => ([(0, 1), (d - 1, d - 1)], 2),
            _ if x == d - 1 => ([(d - 2, d - 1), (0, 0)], 2),
            _ => ([(lo, hi), (0, 0)], 1),
        }
    }
}

/// Applies the permutation `order` to `data` using `scratch` (swapped in).
pub fn permute<T: Copy + Send + Sync>(data: &mut Vec<T>, scratch: &mut Vec<T>, order: &[u32]) {
    use rayon::prelude::*;
    scratch.clear();
    // The room `data` holds goes with its values (a scene's reserved capacity).
    scratch.reserve_exact(data.capacity());
    scratch.par_extend(order.par_iter().with_min_len(4096).map(|&i| data[i as usize]));
    std::mem::swap(data, scratch);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic scatter of points (xorshift), some outside the grid.
    fn points(n: usize) -> Vec<Vec3> {
        let mut s = 0x9e3779b97f4a7c15u64;
        let mut r = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n).map(|_| Vec3::new(r() * 1.2 - 0.1, r() * 0.6 - 0.05, r() * 0.3)).collect()
    }

    #[test]
    fn grid_query_equals_brute_force() {
        let h = 0.07;
        let bounds = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 0.5, 0.3));
        let mut pts = points(3000);
        let mut grid = Grid::new(bounds, h, [false; 3]);
        let (mut cells, mut order, mut scratch) = (Vec::new(), Vec::new(), Vec::new());
        grid.sort(&pts, &mut cells, &mut order);
        permute(&mut pts, &mut scratch, &order);
        // Sorted by cell: cell ids never decrease.
        assert!(pts.windows(2).all(|w| grid.cell_of(w[0]) <= grid.cell_of(w[1])));
        for (i, &p) in pts.iter().enumerate() {
            let mut found = Vec::new();
            grid.for_each_run(p, |run| {
                found.extend(run.filter(|&j| (pts[j] - p).length_squared() < h * h));
            });
            found.sort_unstable();
            let brute: Vec<usize> = (0..pts.len()).filter(|&j| (pts[j] - p).length_squared() < h * h).collect();
            // Points outside the grid are clamped into border cells, which can
            // only drop neighbours that are themselves far outside; inside the
            // grid the query must be exact.
            if bounds.contains(p) {
                assert_eq!(found, brute, "particle {i} at {p}");
            }
        }
    }

    #[test]
    fn periodic_query_finds_the_nearest_images() {
        use crate::periodic::Periodicity;
        // Periods of 2.3, 2 and 5.7 supports: a block wrapping on itself, the smallest
        // period allowed, and a wide one.
        let h = 0.1;
        let bounds = Aabb::new(Vec3::new(-0.1, 0.0, 0.2), Vec3::new(0.13, 0.2, 0.77));
        for axes in [[true, false, false], [false, true, true], [true, true, true]] {
            let wrap = Periodicity::new(bounds, axes);
            let mut pts: Vec<Vec3> =
                points(2000).into_iter().map(|p| wrap.wrap(bounds.min + p * bounds.size())).collect();
            let mut grid = Grid::new(bounds, h, axes);
            let (mut cells, mut order, mut scratch) = (Vec::new(), Vec::new(), Vec::new());
            grid.sort(&pts, &mut cells, &mut order);
            permute(&mut pts, &mut scratch, &order);
            let near = |p: Vec3, q: Vec3| wrap.image(p - q).length_squared() < h * h;
            for &p in pts.iter().filter(|p| bounds.contains(**p)) {
                let mut found = Vec::new();
                grid.for_each_run(p, |run| found.extend(run.filter(|&j| near(p, pts[j]))));
                found.sort_unstable();
                let brute: Vec<usize> = (0..pts.len()).filter(|&j| near(p, pts[j])).collect();
                assert_eq!(found, brute, "axes {axes:?}, particle at {p}");
            }
        }
    }

    #[test]
    fn permutation_is_a_bijection() {
        let pts = points(500);
        let mut grid = Grid::new(Aabb::new(Vec3::ZERO, Vec3::ONE), 0.1, [false; 3]);
        let (mut cells, mut order) = (Vec::new(), Vec::new());
        grid.sort(&pts, &mut cells, &mut order);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..500).collect::<Vec<u32>>());
    }
}
