//! Neighbour lists of the CPU backend: found once per step by the density pass and
//! read by every later pass of the step (forces, XSPH, module passes).
//!
//! Particles are handled in chunks of [`CHUNK`] consecutive (cell-sorted) slots, one
//! rayon task each; each chunk keeps its own compressed rows, so chunks fill in
//! parallel without a merge (~140 bytes per particle, a 1.5x speed-up over
//! searching twice).
//!
//! A pass that walks the same rows many times in a step (DFSPH's solves) may keep
//! each pair's kernel gradient beside its row ([`ChunkNeighbors::keep_gradients`]):
//! 12 bytes per neighbour, allocated only by the schemes that ask for it.

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
    /// particle and `wall(k, b)` for every wall neighbour `b`, in the rows' order: the
    /// pairs' kernel gradients, for passes that walk the rows again within the step.
    pub fn keep_gradients(&mut self, fluid: impl Fn(usize, usize) -> Vec3, wall: impl Fn(usize, usize) -> Vec3) {
        let rows = self.fluid_start.len() - 1;
        self.fluid_grad.clear();
        self.wall_grad.clear();
        for k in 0..rows {
            let (f, w) = (
                self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize,
                self.wall_start[k] as usize..self.wall_start[k + 1] as usize,
            );
            self.fluid_grad.extend(self.fluid[f].iter().map(|&j| fluid(k, j as usize)));
            self.wall_grad.extend(self.walls[w].iter().map(|&b| wall(k, b as usize)));
        }
    }

    /// The kept gradients of the chunk's `k`-th particle's particle neighbours, in
    /// the order of [`Self::fluid`] (see [`Self::keep_gradients`]).
    #[inline(always)]
    pub fn fluid_gradients(&self, k: usize) -> &[Vec3] {
        debug_assert_eq!(self.fluid_grad.len(), self.fluid.len(), "gradients kept for this step's rows");
        &self.fluid_grad[self.fluid_start[k] as usize..self.fluid_start[k + 1] as usize]
    }

    /// The kept gradients of the chunk's `k`-th particle's wall neighbours, in the
    /// order of [`Self::walls`].
    #[inline(always)]
    pub fn wall_gradients(&self, k: usize) -> &[Vec3] {
        debug_assert_eq!(self.wall_grad.len(), self.walls.len(), "gradients kept for this step's rows");
        &self.wall_grad[self.wall_start[k] as usize..self.wall_start[k + 1] as usize]
    }
}

/// The neighbour lists of every chunk of the step.
#[derive(Debug, Default)]
pub struct NeighborLists {
    /// One entry per chunk of [`CHUNK`] particles.
    pub chunks: Vec<ChunkNeighbors>,
}
