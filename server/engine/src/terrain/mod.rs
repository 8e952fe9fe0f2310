//! Terrain: a heightfield wall under `[min, max]` in x and z (y up), from a
//! procedural mountain slope or a grayscale PNG ([`spec`]).
//!
//! Every source is rasterised once at build into a regular grid of heights
//! ([`HeightGrid`], [`source`]); height and normal anywhere come from bilinear
//! interpolation of that grid ([`HeightGrid::eval`]), the same arithmetic the GPU's
//! drift kernel does from a storage buffer of the heights (`integrate.wgsl`).
//!
//! The surface is sampled with `layers` layers of boundary particles below it
//! ([`sample_surface`]), so density and pressure near the ground work through the
//! Akinci wall machinery with every scheme; fluid a block would place under the
//! ground is dropped at build ([`HeightGrid::buried`]).
//!
//! The ground a particle meets is the core attribute [`GROUND`] (`ground_height`):
//! every terrain's node heights, one terrain after another, state that starts as the
//! raster and that a module may change while the scene runs (a snow cover that grows
//! is ground particles land on). The wall particles and the viewer's terrain mesh
//! stay on the raster.
//!
//! After every drift ([`TerrainConstraint::apply`]), a particle below the surface is
//! put back on it (vertically) and loses its velocity into it; a particle in contact
//! (closer than one particle spacing to the surface) then feels Coulomb friction, the
//! basal friction law of avalanche and debris-flow models (Savage & Hutter 1989):
//! its tangential speed shrinks by `mu` times the normal load of the step, the normal
//! speed removed plus gravity's normal component times dt (m/s), to zero at most,
//! never reversing. With `mu` the friction coefficient, fluid on a slope steeper than
//! `atan(mu)` slides with acceleration `g (sin a - mu cos a)`; on a gentler slope
//! friction cancels gravity's pull along the slope and the contact layer stays put.

pub mod source;
pub mod spec;

use crate::attrs::{AttrSpec, Elem, Role};
use crate::math::{Real, Vec3};
use std::sync::Arc;

/// The space of the terrains' nodes (all terrains', one after another).
pub const GROUND_SPACE: &str = "ground";

/// The ground's height at every terrain node (m): the raster's at first; modules may
/// write it (a growing snow cover), and the drift's terrain constraint reads it.
pub static GROUND: AttrSpec = AttrSpec {
    name: "ground_height",
    elem: Elem::F32,
    unit: "m",
    role: Role::State,
    added_later: true,
    space: GROUND_SPACE,
    module: "core",
    about: "Height of the ground at each terrain node.",
};

/// A terrain's heights on a regular grid: node `(i, k)` at
/// `(min.x + i cell.x, min.z + k cell.z)`, stored at `k nx + i`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    /// Footprint's lower corner `[x, z]` (m).
    pub min: [Real; 2],
    /// Distance between nodes `[x, z]` (m).
    pub cell: [Real; 2],
    /// Nodes along x (at least 2).
    pub nx: u32,
    /// Nodes along z (at least 2).
    pub nz: u32,
    /// Heights (m), row by row along x.
    pub heights: Vec<Real>,
}

impl HeightGrid {
    /// Footprint's upper corner `[x, z]` (m).
    pub fn max(&self) -> [Real; 2] {
        [self.min[0] + self.cell[0] * (self.nx - 1) as Real, self.min[1] + self.cell[1] * (self.nz - 1) as Real]
    }

    /// Whether `(x, z)` lies over the footprint.
    pub fn covers(&self, x: Real, z: Real) -> bool {
        let max = self.max();
        x >= self.min[0] && x <= max[0] && z >= self.min[1] && z <= max[1]
    }

    /// Height (m) and unit upward normal at `(x, z)`, bilinear in the grid's cell
    /// (clamped to the footprint); the normal is that of the bilinear patch.
    pub fn eval(&self, x: Real, z: Real) -> (Real, Vec3) {
        self.eval_on(&self.heights, x, z)
    }

    /// [`HeightGrid::eval`] with heights `heights` at the grid's nodes in place of
    /// its own (the ground as it is now: see [`GROUND`]).
    pub fn eval_on(&self, heights: &[Real], x: Real, z: Real) -> (Real, Vec3) {
        let u = ((x - self.min[0]) / self.cell[0]).clamp(0.0, (self.nx - 1) as Real);
        let w = ((z - self.min[1]) / self.cell[1]).clamp(0.0, (self.nz - 1) as Real);
        let i = (u.floor() as u32).min(self.nx - 2);
        let k = (w.floor() as u32).min(self.nz - 2);
        let (fu, fw) = (u - i as Real, w - k as Real);
        let at = |i: u32, k: u32| heights[(k * self.nx + i) as usize];
        let (h00, h10, h01, h11) = (at(i, k), at(i + 1, k), at(i, k + 1), at(i + 1, k + 1));
        let h = (h00 * (1.0 - fu) + h10 * fu) * (1.0 - fw) + (h01 * (1.0 - fu) + h11 * fu) * fw;
        let dx = ((h10 - h00) * (1.0 - fw) + (h11 - h01) * fw) / self.cell[0];
        let dz = ((h01 - h00) * (1.0 - fu) + (h11 - h10) * fu) / self.cell[1];
        (h, Vec3::new(-dx, 1.0, -dz).normalize())
    }

    /// Whether a particle at `x` of a lattice of `spacing` lies under the ground or
    /// closer than half a spacing to it (where it would overlap the wall particles).
    pub fn buried(&self, x: Vec3, spacing: Real) -> bool {
        if !self.covers(x.x, x.z) {
            return false;
        }
        let (h, n) = self.eval(x.x, x.z);
        (x.y - h) * n.y < 0.5 * spacing
    }
}

/// Removes the particles (positions and their velocities) that a terrain among `grids`
/// buries on a lattice of `spacing` ([`HeightGrid::buried`]).
pub fn drop_buried(grids: &[Option<Arc<HeightGrid>>], spacing: Real, x: &mut Vec<Vec3>, v: &mut Vec<Vec3>) {
    let terrains: Vec<&HeightGrid> = grids.iter().flatten().map(|g| &**g).collect();
    if terrains.is_empty() {
        return;
    }
    let keep: Vec<bool> = x.iter().map(|&p| !terrains.iter().any(|g| g.buried(p, spacing))).collect();
    let mut k = keep.iter();
    x.retain(|_| *k.next().expect("one flag per particle"));
    let mut k = keep.iter();
    v.retain(|_| *k.next().expect("one flag per particle"));
}

/// Boundary particles of a terrain: `layers` layers below the surface, the `l`-th
/// `(l + 1/2) spacing` along the inward normal, on rows about `spacing` apart along z
/// and, within a row, about `spacing` apart along the surface (so a steep slope is
/// sampled as densely as flat ground).
pub fn sample_surface(grid: &HeightGrid, spacing: Real, layers: u32) -> Vec<Vec3> {
    let max = grid.max();
    let (lx, lz) = (max[0] - grid.min[0], max[1] - grid.min[1]);
    let rows = (lz / spacing).round().max(1.0) as u32;
    let fine = (4.0 * lx / spacing).ceil().max(1.0) as u32;
    let mut out = Vec::new();
    for r in 0..rows {
        let z = grid.min[1] + (r as Real + 0.5) * lz / rows as Real;
        // Arc length along the row at `fine` steps, then samples at equal arc lengths.
        let xs: Vec<Real> = (0..=fine).map(|s| grid.min[0] + lx * s as Real / fine as Real).collect();
        let mut arc = vec![0.0; xs.len()];
        for s in 1..xs.len() {
            let dy = grid.eval(xs[s], z).0 - grid.eval(xs[s - 1], z).0;
            arc[s] = arc[s - 1] + (xs[s] - xs[s - 1]).hypot(dy);
        }
        let total = arc[fine as usize];
        let count = (total / spacing).round().max(1.0) as u32;
        let mut s = 0;
        for j in 0..count {
            let target = (j as Real + 0.5) * total / count as Real;
            while arc[s + 1] < target {
                s += 1;
            }
            let t = (target - arc[s]) / (arc[s + 1] - arc[s]);
            let x = xs[s] + t * (xs[s + 1] - xs[s]);
            let (h, n) = grid.eval(x, z);
            for l in 0..layers {
                out.push(Vec3::new(x, h, z) - n * ((l as Real + 0.5) * spacing));
            }
        }
    }
    out
}

/// A terrain's non-penetration and Coulomb friction constraint.
#[derive(Debug, Clone, PartialEq)]
pub struct TerrainConstraint {
    /// The heights.
    pub grid: Arc<HeightGrid>,
    /// Coulomb friction coefficient (dimensionless).
    pub friction: Real,
    /// Particles closer than this to the surface are in contact (m): one spacing.
    pub contact: Real,
    /// Index of its first node in [`GROUND`].
    pub first: usize,
}

impl TerrainConstraint {
    /// Puts a particle under the surface back on it, removing its velocity into the
    /// surface; then, in contact, reduces its tangential speed by `friction` times the
    /// step's normal load (the normal speed removed plus `-(g dt) . n`, `g_dt` being
    /// gravity times the drift's dt), to zero at most. `ground` is [`GROUND`]'s
    /// values (every terrain's; this one's from `first`).
    #[inline]
    pub fn apply(&self, x: &mut Vec3, v: &mut Vec3, g_dt: Vec3, ground: &[Real]) {
        if !self.grid.covers(x.x, x.z) {
            return;
        }
        let (h, n) = self.grid.eval_on(&ground[self.first..], x.x, x.z);
        let mut removed = 0.0;
        if x.y < h {
            x.y = h;
            let vn = v.dot(n);
            if vn < 0.0 {
                *v -= n * vn;
                removed = -vn;
            }
        }
        if (x.y - h) * n.y >= self.contact {
            return;
        }
        let load = removed + (-g_dt.dot(n)).max(0.0);
        let vn = v.dot(n);
        let tangential = *v - n * vn;
        let speed = tangential.length();
        if speed > 0.0 {
            let keep = (speed - self.friction * load).max(0.0) / speed;
            *v = n * vn + tangential * keep;
        }
    }
}

#[cfg(test)]
mod tests;
