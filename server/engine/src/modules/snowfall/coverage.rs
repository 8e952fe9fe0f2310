//! The snow thesis's coverage (its eqs. 2.1-2.2): where snow can reach and stay.
//!
//! `f_p = f_e f_inc`: `f_e` is the share of sampled directions from which the point
//! is exposed, tested against occlusion depth maps (eq. 2.2,
//! `sum (D_testdepth - D_depth >= 0) / M_samples`), and `f_inc` the inclination
//! factor, 1 on flat ground and 0 on a vertical face. The thesis's text does not
//! say which directions it samples nor the form of `f_inc`; Floe samples the
//! vertical and two rings of eight directions, at half the cone's angle and at the
//! cone's (`snowfall.coverage_cone`, degrees from the vertical), and takes
//! `f_inc = cos(theta)`, theta the ground's inclination.
//!
//! The thesis renders a depth map from each sampled direction (shadow maps) and
//! compares the point's depth with it; Floe does what those maps approximate, at
//! no resolution of their own: a direction is occluded when the ray from the point
//! (the ground at a cell's centre) along it meets an object (boxes and cylinders,
//! intersected exactly, so a thin roof occludes and the sky past its edge does
//! not), a mesh's column over a cell (see [`super::columns`]) or passes under the
//! ground (the grid's ground heights, marched in half-cell steps until the ray
//! rises above the highest of them or leaves the grid).
//!
//! Coverage and depth are two different quantities: depth (`snow_depth`) is the
//! snow the flakes laid, which wind moves and which grows with time; coverage
//! (`coverage`, 0 to 1) is how much of the ground's surface the thesis's model
//! would draw white, from geometry alone. Objects do not move, so it is computed
//! once, when the scene is built.

use super::SnowfallConsts;
use super::flakes::centre;
use crate::math::Vec3;

/// The sampled directions: the vertical, and rings of eight at half the cone's
/// angle and at the cone's (unit vectors pointing up).
pub fn directions(cone_degrees: f32) -> Vec<Vec3> {
    let mut out = vec![Vec3::Y];
    for ring in [0.5, 1.0] {
        let theta = (ring * cone_degrees).to_radians();
        for k in 0..8 {
            let phi = k as f32 * std::f32::consts::TAU / 8.0;
            out.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()));
        }
    }
    out
}

/// The coverage of each cell's ground, with the meshes' columns over the cells
/// (`columns`: bottom and top, none where the top is below the bottom).
pub fn coverage(c: &SnowfallConsts, bed: &[f32], columns: &[[f32; 4]], cone_degrees: f32) -> Vec<f32> {
    let ground = Ground::new(c, bed, columns);
    let dirs = directions(cone_degrees);
    let at = |k: usize, y: f32| {
        let (x, z) = centre(c, k);
        Vec3::new(x, y, z)
    };
    (0..bed.len()).map(|k| ground.exposure(at(k, bed[k]), &dirs) * inclination(c, bed, k)).collect()
}

/// The coverage of the top of the object over each cell's centre (`tops`, m;
/// [`super::NO_OBJECT`] where none: 0 there): the tops are flat, so it is their
/// exposure alone.
pub fn top_coverage(
    c: &SnowfallConsts,
    bed: &[f32],
    columns: &[[f32; 4]],
    tops: &[f32],
    cone_degrees: f32,
) -> Vec<f32> {
    let ground = Ground::new(c, bed, columns);
    let dirs = directions(cone_degrees);
    let on = |k: usize| {
        let (x, z) = centre(c, k);
        Vec3::new(x, tops[k] + 1e-4, z)
    };
    (0..bed.len()).map(|k| if tops[k] > super::NO_OBJECT { ground.exposure(on(k), &dirs) } else { 0.0 }).collect()
}

/// What rays meet besides the objects: the ground's heights and the meshes'
/// columns over the cells.
struct Ground<'a> {
    c: &'a SnowfallConsts,
    bed: &'a [f32],
    columns: &'a [[f32; 4]],
    /// The highest of both (m): a ray above it meets neither.
    highest: f32,
}

impl<'a> Ground<'a> {
    fn new(c: &'a SnowfallConsts, bed: &'a [f32], columns: &'a [[f32; 4]]) -> Self {
        let highest = bed.iter().chain(columns.iter().map(|c| &c[1])).copied().fold(f32::NEG_INFINITY, f32::max);
        Self { c, bed, columns, highest }
    }

    /// The share of directions `dirs` from which `p` sees the sky.
    fn exposure(&self, p: Vec3, dirs: &[Vec3]) -> f32 {
        dirs.iter().filter(|d| !self.occluded(p, **d)).count() as f32 / dirs.len() as f32
    }

    /// Whether the ray from `p` along `d` (pointing up) meets an object, a mesh's
    /// column or the ground.
    fn occluded(&self, p: Vec3, d: Vec3) -> bool {
        let c = self.c;
        if c.objects.iter().any(|o| hits(o, p, d)) {
            return true;
        }
        let across = d.x.hypot(d.z);
        if across == 0.0 {
            // Straight up: only a column over the point's own cell.
            return self.columns[super::flakes::cell(c, p.x, p.z)][1] > p.y + 1e-4;
        }
        // Half a cell along the ground per step, from the first step on; a column
        // is met where the heights the ray spans over the step (from `below` to
        // the end's) overlap it, however steep the ray.
        let step = 0.5 * c.cell / across;
        let (mut t, mut below) = (step, p.y);
        loop {
            let q = p + d * t;
            if below > self.highest || !super::flakes::over(c.area_min, c.area_max, q) {
                return false;
            }
            let k = super::flakes::cell(c, q.x, q.z);
            let [bottom, top, ..] = self.columns[k];
            if self.bed[k] > q.y + 1e-4 || (q.y >= bottom && below <= top) {
                return true;
            }
            (t, below) = (t + step, q.y);
        }
    }
}

/// Whether the ray `p + t d`, `t > 0`, meets object `o` (a box by its slabs, a
/// cylinder by its circle and its heights).
fn hits(o: &[[f32; 4]; 2], p: Vec3, d: Vec3) -> bool {
    let [a, b] = *o;
    // The ray's interval of t inside the object, narrowed by each bound in turn.
    let mut span = (0.0f32, f32::INFINITY);
    if a[3] == 0.0 {
        clip(&mut span, a[0], b[0], p.x, d.x);
        clip(&mut span, a[2], b[2], p.z, d.z);
    } else {
        // |p_xz + t d_xz - centre| <= radius.
        let (ox, oz) = (p.x - a[0], p.z - a[2]);
        let qa = d.x * d.x + d.z * d.z;
        let qb = ox * d.x + oz * d.z;
        let qc = ox * ox + oz * oz - b[0] * b[0];
        if qa == 0.0 {
            if qc > 0.0 {
                return false;
            }
        } else {
            let disc = qb * qb - qa * qc;
            if disc < 0.0 {
                return false;
            }
            let root = disc.sqrt();
            span = (span.0.max((-qb - root) / qa), span.1.min((-qb + root) / qa));
        }
    }
    clip(&mut span, a[1], b[1], p.y, d.y);
    span.0 <= span.1 && span.1 > 0.0
}

/// Narrows `span` to where `from + t dir` lies in `[lo, hi]`.
fn clip(span: &mut (f32, f32), lo: f32, hi: f32, from: f32, dir: f32) {
    if dir == 0.0 {
        if from < lo || from > hi {
            span.1 = -1.0;
        }
    } else {
        let (t0, t1) = ((lo - from) / dir, (hi - from) / dir);
        *span = (span.0.max(t0.min(t1)), span.1.min(t0.max(t1)));
    }
}

/// `cos(theta)` of the ground at cell `k`, its slope by differences of the bed
/// between the neighbouring cells (one-sided at the grid's edges).
pub fn inclination(c: &SnowfallConsts, bed: &[f32], k: usize) -> f32 {
    let (nx, nz) = (c.nx as usize, c.nz as usize);
    let (i, j) = (k % nx, k / nx);
    let slope = |lo: usize, hi: usize, n: usize| {
        if n == 0 { 0.0 } else { (bed[hi] - bed[lo]) / (c.cell * n as f32) }
    };
    let (xl, xh) = (i.saturating_sub(1), (i + 1).min(nx - 1));
    let (zl, zh) = (j.saturating_sub(1), (j + 1).min(nz - 1));
    let dx = slope(j * nx + xl, j * nx + xh, xh - xl);
    let dz = slope(zl * nx + i, zh * nx + i, zh - zl);
    Vec3::new(-dx, 1.0, -dz).normalize().y
}
