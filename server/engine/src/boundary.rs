//! Static boundary particles (Akinci, Ihmsen, Akinci, Solenthaler & Teschner 2012,
//! "Versatile rigid-fluid coupling for incompressible SPH", ACM TOG 31(4)).
//!
//! Each wall particle b carries a pseudo-mass `psi_b = rho0 V_b` with
//! `V_b = 1 / sum_k W(x_b - x_k)` over wall particles k (eqs. 4-5), so an uneven
//! or single-layer sampling still contributes the right density near a wall.
//! `rho0` is the rest density of the fluid particle the wall acts on, so there is
//! one pseudo-mass per wall particle and material.
//!
//! Floe rescales that volume by `gamma = S_slab / S_lattice`: the kernel sum a wall
//! particle sees inside a flat wall of `layers` lattice layers, over the sum a
//! particle sees in a full lattice. A flat wall sampled on the fluid lattice then
//! gives the first fluid layer exactly `rho0` (unscaled, Akinci's volume over-
//! estimates it by 6 % with the cubic spline and 12 % with poly6 at support two
//! spacings, which a stiff Tait equation turns into a jet off the walls), while an
//! uneven sampling keeps Akinci's compensation relative to that flat wall.

use crate::kernel::Kernel;
use crate::math::{Aabb, Real, Vec3};
use crate::neighbors::{Grid, permute};
use crate::periodic::Periodicity;
use crate::terrain::{HeightGrid, TerrainConstraint};
use rayon::prelude::*;
use std::sync::Arc;

/// Wall particles sorted by cell, with their pseudo-masses and their own grid.
#[derive(Debug, Clone)]
pub struct BoundaryParticles {
    /// Positions (m), sorted by cell of `grid`.
    pub positions: Vec<Vec3>,
    /// Pseudo-masses `psi_b = rho0 V_b` (kg), per material (index: material).
    pub psi: Vec<Vec<Real>>,
    /// Neighbour grid over `positions` (built once: walls do not move).
    pub grid: Grid,
}

impl BoundaryParticles {
    /// Sorts `positions` into a grid over `bounds` (the domain's extent on its periodic
    /// axes) and computes their pseudo-masses for each material's rest density in
    /// `rho0`; `spacing` and `layers` describe the lattice the walls were sampled on.
    pub fn new(
        mut positions: Vec<Vec3>,
        kernel: &Kernel,
        rho0: &[Real],
        bounds: Aabb,
        periodic: &Periodicity,
        spacing: Real,
        layers: u32,
    ) -> Self {
        let gamma = lattice_sum(kernel, spacing, Some(layers)) / lattice_sum(kernel, spacing, None);
        let mut grid = Grid::new(periodic.fit(bounds), kernel.support(), periodic.axes);
        let (mut cells, mut order, mut scratch) = (Vec::new(), Vec::new(), Vec::new());
        grid.sort(&positions, &mut cells, &mut order);
        permute(&mut positions, &mut scratch, &order);
        let h2 = kernel.support() * kernel.support();
        let sums: Vec<Real> = positions
            .par_iter()
            .map(|&x| {
                let mut sum = 0.0;
                grid.for_each_run(x, |run| {
                    for &y in &positions[run] {
                        let r2 = periodic.image(x - y).length_squared();
                        if r2 < h2 {
                            sum += kernel.w_r2(r2);
                        }
                    }
                });
                sum
            })
            .collect();
        let psi = rho0.iter().map(|&rho0| sums.iter().map(|&sum| rho0 * gamma / sum).collect()).collect();
        Self { positions, psi, grid }
    }

    /// Number of wall particles.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }
}

/// `sum W(x)` over the points of a cubic lattice of `spacing` around one of its
/// points: the full lattice, or only the `layers` layers `0..layers` of a slab
/// (the point in its first layer).
pub fn lattice_sum(kernel: &Kernel, spacing: Real, layers: Option<u32>) -> Real {
    let reach = (kernel.support() / spacing).ceil() as i32;
    let k_range = match layers {
        Some(l) => 0..=(l as i32 - 1),
        None => -reach..=reach,
    };
    let mut sum = 0.0;
    for k in k_range {
        for j in -reach..=reach {
            for i in -reach..=reach {
                sum += kernel.w_r2((Vec3::new(i as Real, j as Real, k as Real) * spacing).length_squared());
            }
        }
    }
    sum
}

/// The geometric side of a wall: particles that cross its surface are put back
/// on it and lose their velocity into it.
///
/// Akinci's wall particles push only as hard as the fluid particle's own
/// pressure, and pressure is clamped at zero, so a thin splash landing on a floor
/// (density below rest) feels no push at all and could fall through a single
/// layer. This projection, applied after every drift, makes "no fluid crosses a
/// wall" hold regardless; in a settled or dense flow it never triggers.
#[derive(Debug, Clone, PartialEq)]
pub enum WallConstraint {
    /// Keep particles inside `[min, max]` on the faces that are closed.
    Box {
        /// Lower corner of the free interior (m).
        min: Vec3,
        /// Upper corner (m).
        max: Vec3,
        /// Per axis, whether the lower / upper face is a wall.
        closed: [[bool; 2]; 3],
        /// How far outside a face the constraint reaches (m): its wall thickness.
        reach: Real,
    },
    /// Keep particles on the normal's side of a rectangle.
    Plane {
        /// Centre (m).
        center: Vec3,
        /// Unit normal into the fluid.
        normal: Vec3,
        /// Unit tangents and half edge lengths (m).
        tangents: [(Vec3, Real); 2],
        /// How far behind the surface the constraint reaches (m).
        reach: Real,
    },
    /// Keep particles above a heightfield, with Coulomb friction in contact.
    Terrain(TerrainConstraint),
}

impl WallConstraint {
    /// The constraint of a scene wall sampled at `spacing`; a terrain's comes with
    /// its rasterised heights (`grid`, `None` for the other walls).
    pub fn new(b: &crate::scene::Boundary, spacing: Real, grid: Option<&Arc<HeightGrid>>) -> Self {
        use crate::scene::{Boundary, Face};
        match b {
            Boundary::Box { min, max, open, layers } => {
                let is_open = |f: Face| open.contains(&f);
                WallConstraint::Box {
                    min: (*min).into(),
                    max: (*max).into(),
                    closed: [
                        [!is_open(Face::MinusX), !is_open(Face::PlusX)],
                        [!is_open(Face::MinusY), !is_open(Face::PlusY)],
                        [!is_open(Face::MinusZ), !is_open(Face::PlusZ)],
                    ],
                    reach: (*layers as Real + 1.0) * spacing,
                }
            }
            Boundary::Plane { center, normal, size, layers } => {
                let n = Vec3::from(*normal).normalize();
                let t1 = n.any_orthonormal_vector();
                WallConstraint::Plane {
                    center: (*center).into(),
                    normal: n,
                    tangents: [(t1, 0.5 * size[0]), (n.cross(t1), 0.5 * size[1])],
                    reach: (*layers as Real + 1.0) * spacing,
                }
            }
            Boundary::Terrain(t) => WallConstraint::Terrain(TerrainConstraint {
                grid: grid.expect("a terrain is built with its height grid").clone(),
                friction: t.friction,
                contact: spacing,
                first: 0,
            }),
        }
    }

    /// Projects `x` back onto the wall if it crossed it, removing the velocity
    /// component into the wall; a terrain also applies friction, for which `g_dt` is
    /// gravity times the drift's dt (m/s), and meets the ground as `ground` has it
    /// (the core's `ground_height`: every terrain's node heights).
    #[inline]
    pub fn apply(&self, x: &mut Vec3, v: &mut Vec3, g_dt: Vec3, ground: &[Real]) {
        match self {
            WallConstraint::Box { min, max, closed, reach } => {
                // Only particles within the wall's slab (not far outside the box,
                // e.g. above an open top) are concerned.
                let outer_min = *min - Vec3::splat(*reach);
                let outer_max = *max + Vec3::splat(*reach);
                if !(x.cmpge(outer_min).all() && x.cmple(outer_max).all()) {
                    return;
                }
                for a in 0..3 {
                    if closed[a][0] && x[a] < min[a] {
                        x[a] = min[a];
                        v[a] = v[a].max(0.0);
                    }
                    if closed[a][1] && x[a] > max[a] {
                        x[a] = max[a];
                        v[a] = v[a].min(0.0);
                    }
                }
            }
            WallConstraint::Plane { center, normal, tangents, reach } => {
                let rel = *x - *center;
                let depth = rel.dot(*normal);
                if depth >= 0.0 || depth < -reach {
                    return;
                }
                if tangents.iter().any(|(t, half)| rel.dot(*t).abs() > *half) {
                    return;
                }
                *x -= *normal * depth;
                let vn = v.dot(*normal);
                if vn < 0.0 {
                    *v -= *normal * vn;
                }
            }
            WallConstraint::Terrain(t) => t.apply(x, v, g_dt, ground),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Boundary, Face};

    #[test]
    fn box_constraint_returns_escaped_particles() {
        let b = Boundary::Box { min: [0.0; 3], max: [1.0; 3], open: vec![Face::PlusY], layers: 1 };
        let c = WallConstraint::new(&b, 0.1, None);
        let (mut x, mut v) = (Vec3::new(-0.05, 0.5, 0.5), Vec3::new(-1.0, 0.0, 2.0));
        c.apply(&mut x, &mut v, Vec3::ZERO, &[]);
        assert_eq!((x, v), (Vec3::new(0.0, 0.5, 0.5), Vec3::new(0.0, 0.0, 2.0)));
        // The open top lets particles out.
        let (mut x, mut v) = (Vec3::new(0.5, 1.05, 0.5), Vec3::Y);
        c.apply(&mut x, &mut v, Vec3::ZERO, &[]);
        assert_eq!(x.y, 1.05);
    }

    #[test]
    fn plane_constraint_acts_only_behind_its_rectangle() {
        let b = Boundary::Plane { center: [0.0; 3], normal: [0.0, 1.0, 0.0], size: [1.0, 1.0], layers: 1 };
        let c = WallConstraint::new(&b, 0.1, None);
        let (mut x, mut v) = (Vec3::new(0.1, -0.05, 0.1), Vec3::new(1.0, -1.0, 0.0));
        c.apply(&mut x, &mut v, Vec3::ZERO, &[]);
        assert!((x - Vec3::new(0.1, 0.0, 0.1)).length() < 1e-6 && (v - Vec3::X).length() < 1e-6);
        let (mut x, mut v) = (Vec3::new(2.0, -0.05, 0.0), -Vec3::Y);
        c.apply(&mut x, &mut v, Vec3::ZERO, &[]);
        assert_eq!(x.y, -0.05);
    }

    #[test]
    fn flat_lattice_wall_gives_rest_density() {
        // A fluid particle half a spacing above a one-layer floor sampled on the
        // lattice sees exactly the full lattice sum (support = 2 spacings).
        use crate::kernel::{Kernel, KernelKind};
        for kind in [KernelKind::Mueller, KernelKind::CubicSpline, KernelKind::WendlandC2] {
            let d = 0.1;
            let k = Kernel::new(kind, 2.0 * d);
            let full = lattice_sum(&k, d, None);
            let floor = crate::sampling::sample_boundary(
                &Boundary::Box { min: [-1.0; 3], max: [1.0; 3], open: vec![], layers: 1 },
                d,
                [false; 3],
                None,
            );
            let walls = BoundaryParticles::new(
                floor,
                &k,
                &[1000.0],
                Aabb::new(Vec3::splat(-1.2), Vec3::splat(1.2)),
                &Periodicity::NONE,
                d,
                1,
            );
            let x = Vec3::new(0.05, -0.95, 0.05);
            let mass = 1000.0 / full;
            let mut rho = 0.0;
            for (i, &b) in walls.positions.iter().enumerate() {
                rho += walls.psi[0][i] * k.w_r2((x - b).length_squared());
            }
            // Fluid: the half lattice above the floor, the particle's own layer included.
            for jy in 0..3 {
                for jx in -3..=3 {
                    for jz in -3..=3 {
                        let p = Vec3::new(jx as f32, jy as f32, jz as f32) * d;
                        rho += mass * k.w_r2(p.length_squared());
                    }
                }
            }
            assert!((rho - 1000.0).abs() < 5.0, "{kind:?}: {rho}");
        }
    }
}
