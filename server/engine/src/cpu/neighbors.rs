//! Neighbour lists of the CPU backend: found once per step by the density pass and
//! read by every later pass of the step (forces, XSPH, module passes).
//!
//! Particles are handled in chunks of [`CHUNK`] consecutive (cell-sorted) slots, one
//! rayon task each; each chunk keeps its own compressed rows, so chunks fill in
//! parallel without a merge (~140 bytes per particle, a 1.5x speed-up over
//! searching twice).
//!
//! A pass that walks the same rows many times in a step (DFSPH's solves) may keep a
//! value per pair beside its row ([`ChunkNeighbors::keep`]): the pair's kernel
//! gradient (12 bytes) or its packed `dW/dr / r` (2 bytes,
//! [`crate::kernel::GradientPacking`]), allocated only by the schemes that ask.

use crate::math::{Real, Vec3};
use crate::neighbors::Grid;
use crate::periodic::Separation;

/// Particles per rayon task: large enough to amortise scheduling.
pub const CHUNK: usize = 512;

/// Appends to `out` the indices of the points of `pts` within the support of
/// `x` (squared distance below `h2`, separations measured by `sep`), from the
/// grid's candidate runs.
///
/// The compaction is branch-free: every candidate is written and the cursor
/// advances only for a hit. About 15 % of candidates are hits, so a branch per
/// candidate would mispredict constantly; this is the hot loop of the step.
#[inline(always)]
pub fn gather<S: Separation>(sep: S, grid: &Grid, pts: &[Vec3], x: Vec3, h2: Real, out: &mut Vec<u32>) {
    grid.for_each_run(x, |run| {
        let mut n = out.len();
        out.resize(n + run.len(), 0);
        for (j, &p) in run.clone().zip(&pts[run]) {
            out[n] = j as u32;
            n += (sep.between(x, p).length_squared() < h2) as usize;
        }
        out.truncate(n);
    });
}

/// Neighbour lists (compressed rows) of one chunk of [`CHUNK`] consecutive particles.
#[derive(Debug, Default)]
pub struct ChunkNeighbors {
    fluid_start: Vec<u32>,
    fluid: Vec<u32>,
    wall_start: Vec<u32>,
    walls: Vec<u32>,
    fluid_grad: Vec<Vec3>,
    wall_grad: Vec<Vec3>,
    fluid_packed: Vec<u16>,
    wall_packed: Vec<u16>,
    fluid_weight: Vec<f32>,
    wall_weight: Vec<f32>,
}

impl ChunkNeighbors {
    /// Empties the lists for a new step.
    pub fn clear(&mut self) {
        self.fluid_start.clear();
        self.fluid_start.push(0);
        self.fluid.clear();
        self.wall_start.clear();
        self.wall_start.push(0);
        self.walls.clear();
        self.fluid_grad.clear();
        self.wall_grad.clear();
        self.fluid_packed.clear();
        self.wall_packed.clear();
        self.fluid_weight.clear();
        self.wall_weight.clear();
    }

    /// Appends the next particle's neighbours: particles of `pos` on `grid` and wall
    /// particles of `walls` on `wall_grid` within the support (squared: `h2`) of `x`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn push<S: Separation>(
        &mut self,
        sep: S,
        grid: &Grid,
        pos: &[Vec3],
        wall_grid: &Grid,
        walls: &[Vec3],
        x: Vec3,
        h2: Real,
    ) {
        gather(sep, grid, pos, x, h2, &mut self.fluid);
        self.fluid_start.push(self.fluid.len() as u32);
        gather(sep, wall_grid, walls, x, h2, &mut self.walls);
        self.wall_start.push(self.walls.len() as u32);
    }

    /// Particle neighbours (self included) of the chunk's `k`-th particle.
    #[inline(always)]
    pub fn fluid(&self, k: usize) -> &[u32] {
        &self.fluid[self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize]
    }

    /// Wall neighbours of the chunk's `k`-th particle.
    #[inline(always)]
    pub fn walls(&self, k: usize) -> &[u32] {
        &self.walls[self.wall_start[k] as usize..self.wall_start[k + 1] as usize]
    }

    /// Keeps `fluid(k, j)` for every particle neighbour `j` of the chunk's `k`-th
    /// particle and `wall(k, b)` for every wall neighbour `b`, in the rows' order, for
    /// passes that walk the rows again within the step.
    pub fn keep<T: PairValue>(&mut self, fluid: impl Fn(usize, usize) -> T, wall: impl Fn(usize, usize) -> T) {
        let rows = self.fluid_start.len() - 1;
        let (mut fluid_kept, mut wall_kept) = {
            let (f, w) = T::columns_mut(self);
            (std::mem::take(f), std::mem::take(w))
        };
        fluid_kept.clear();
        wall_kept.clear();
        for k in 0..rows {
            let (f, w) = (
                self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize,
                self.wall_start[k] as usize..self.wall_start[k + 1] as usize,
            );
            fluid_kept.extend(self.fluid[f].iter().map(|&j| fluid(k, j as usize)));
            wall_kept.extend(self.walls[w].iter().map(|&b| wall(k, b as usize)));
        }
        let (f, w) = T::columns_mut(self);
        (*f, *w) = (fluid_kept, wall_kept);
    }

    /// The values kept for the chunk's `k`-th particle's particle neighbours, in the
    /// order of [`Self::fluid`] (see [`Self::keep`]).
    #[inline(always)]
    pub fn fluid_kept<T: PairValue>(&self, k: usize) -> &[T] {
        let kept = T::columns(self).0;
        debug_assert_eq!(kept.len(), self.fluid.len(), "values kept for this step's rows");
        &kept[self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize]
    }

    /// The values kept for the chunk's `k`-th particle's wall neighbours, in the
    /// order of [`Self::walls`].
    #[inline(always)]
    pub fn wall_kept<T: PairValue>(&self, k: usize) -> &[T] {
        let kept = T::columns(self).1;
        debug_assert_eq!(kept.len(), self.walls.len(), "values kept for this step's rows");
        &kept[self.wall_start[k] as usize..self.wall_start[k + 1] as usize]
    }
}

/// A value a pass may keep per pair ([`ChunkNeighbors::keep`]): each type has its
/// own columns, so a scene that keeps one never allocates the other.
pub trait PairValue: Copy + Sized {
    /// The particle pairs' and wall pairs' columns.
    fn columns(nb: &ChunkNeighbors) -> (&Vec<Self>, &Vec<Self>);
    /// The same, to fill.
    fn columns_mut(nb: &mut ChunkNeighbors) -> (&mut Vec<Self>, &mut Vec<Self>);
}

impl PairValue for Vec3 {
    fn columns(nb: &ChunkNeighbors) -> (&Vec<Self>, &Vec<Self>) {
        (&nb.fluid_grad, &nb.wall_grad)
    }
    fn columns_mut(nb: &mut ChunkNeighbors) -> (&mut Vec<Self>, &mut Vec<Self>) {
        (&mut nb.fluid_grad, &mut nb.wall_grad)
    }
}

impl PairValue for u16 {
    fn columns(nb: &ChunkNeighbors) -> (&Vec<Self>, &Vec<Self>) {
        (&nb.fluid_packed, &nb.wall_packed)
    }
    fn columns_mut(nb: &mut ChunkNeighbors) -> (&mut Vec<Self>, &mut Vec<Self>) {
        (&mut nb.fluid_packed, &mut nb.wall_packed)
    }
}

impl PairValue for f32 {
    fn columns(nb: &ChunkNeighbors) -> (&Vec<Self>, &Vec<Self>) {
        (&nb.fluid_weight, &nb.wall_weight)
    }
    fn columns_mut(nb: &mut ChunkNeighbors) -> (&mut Vec<Self>, &mut Vec<Self>) {
        (&mut nb.fluid_weight, &mut nb.wall_weight)
    }
}

/// The neighbour lists of every chunk of the step.
#[derive(Debug, Default)]
pub struct NeighborLists {
    /// One entry per chunk of [`CHUNK`] particles.
    pub chunks: Vec<ChunkNeighbors>,
}
