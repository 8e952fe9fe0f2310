//! Periodic boundaries: a domain whose opposite faces along some axes are the same
//! place, so what leaves through one face comes back through the other and
//! particles near one face have neighbours near the other.
//!
//! Pairs use the minimum-image convention (Allen & Tildesley, "Computer Simulation
//! of Liquids", 1987, section 1.5.2): the separation of two particles along a
//! periodic axis of period `L` is the one of `d`, `d - L`, `d + L` whose magnitude is
//! at most `L / 2`. With `L` at least two kernel supports every pair within the
//! support has exactly one such image, so the sums over neighbours are those of an
//! infinite periodic medium. Positions are wrapped back into `[min, min + L)` after
//! every drift; the neighbour grid's cells on a periodic axis tile the period
//! exactly and its 3x3x3 block wraps around.
//!
//! On an open axis [`Periodicity::image`] returns `d` unchanged bit for bit, and the
//! CPU passes of a scene with no periodic axis skip it altogether ([`Separation`]).

use crate::math::{Aabb, Real, Vec3};

/// The periodic axes of a domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Periodicity {
    /// Which of x, y, z are periodic.
    pub axes: [bool; 3],
    /// Lower corner of the domain (m).
    min: Vec3,
    /// Period per axis (m), 0 on open axes.
    period: Vec3,
    /// Half the period (m); the largest float on open axes, which no finite
    /// separation exceeds (GPU compilers may assume there are no infinities).
    half: Vec3,
}

impl Periodicity {
    /// No periodic axis.
    pub const NONE: Self = Self { axes: [false; 3], min: Vec3::ZERO, period: Vec3::ZERO, half: Vec3::splat(Real::MAX) };

    /// `domain` periodic along the axes flagged in `axes`.
    pub fn new(domain: Aabb, axes: [bool; 3]) -> Self {
        let size = domain.size();
        let pick = |a: usize, periodic: Real, open: Real| if axes[a] { periodic } else { open };
        let period = Vec3::new(pick(0, size.x, 0.0), pick(1, size.y, 0.0), pick(2, size.z, 0.0));
        let max = Real::MAX;
        let half = Vec3::new(pick(0, 0.5 * size.x, max), pick(1, 0.5 * size.y, max), pick(2, 0.5 * size.z, max));
        Self { axes, min: domain.min, period, half }
    }

    /// Whether any axis is periodic.
    pub fn any(&self) -> bool {
        self.axes.contains(&true)
    }

    /// Period per axis (m), 0 on open axes.
    pub fn period(&self) -> Vec3 {
        self.period
    }

    /// Half period per axis (m), the largest float on open axes (the GPU's constants).
    pub fn half(&self) -> Vec3 {
        self.half
    }

    /// `bounds` with the domain's extent on the periodic axes (a grid over it then
    /// tiles the period).
    pub fn fit(&self, mut bounds: Aabb) -> Aabb {
        for a in 0..3 {
            if self.axes[a] {
                bounds.min[a] = self.min[a];
                bounds.max[a] = self.min[a] + self.period[a];
            }
        }
        bounds
    }

    /// The minimum image of the separation `d = x_i - x_j` of two wrapped positions.
    #[inline(always)]
    pub fn image(&self, d: Vec3) -> Vec3 {
        let below = Vec3::select(d.cmplt(-self.half), d + self.period, d);
        Vec3::select(d.cmpgt(self.half), d - self.period, below)
    }

    /// `x` moved by whole periods into `[min, min + period)` on the periodic axes.
    #[inline]
    pub fn wrap(&self, mut x: Vec3) -> Vec3 {
        for a in 0..3 {
            if self.axes[a] {
                let (lo, l) = (self.min[a], self.period[a]);
                if x[a] < lo || x[a] >= lo + l {
                    x[a] -= l * ((x[a] - lo) / l).floor();
                    // Rounding can land exactly on the upper face.
                    if x[a] >= lo + l {
                        x[a] = lo;
                    }
                }
            }
        }
        x
    }
}

/// How a pass measures the separation of two particles. The CPU passes are generic
/// over it and pick [`Open`] when a scene has no periodic axis, so open scenes pay
/// nothing for periodicity in their pair loops.
pub trait Separation: Copy + Send + Sync {
    /// `a - b`, or its minimum image.
    fn between(self, a: Vec3, b: Vec3) -> Vec3;
}

/// Plain differences: a domain with no periodic axis.
#[derive(Debug, Clone, Copy)]
pub struct Open;

impl Separation for Open {
    #[inline(always)]
    fn between(self, a: Vec3, b: Vec3) -> Vec3 {
        a - b
    }
}

impl Separation for &Periodicity {
    #[inline(always)]
    fn between(self, a: Vec3, b: Vec3) -> Vec3 {
        self.image(a - b)
    }
}

/// Calls `$body` with `$s` bound to the scene's [`Separation`]: [`Open`] when
/// `$periodic` (a `&Periodicity`) has no periodic axis, the periodicity otherwise.
#[macro_export]
macro_rules! with_separation {
    ($periodic:expr, |$s:ident| $body:expr) => {{
        let periodic: &$crate::periodic::Periodicity = $periodic;
        if periodic.any() {
            let $s = periodic;
            $body
        } else {
            let $s = $crate::periodic::Open;
            $body
        }
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_x() -> Periodicity {
        Periodicity::new(Aabb::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0)), [true, false, false])
    }

    #[test]
    fn open_axes_are_untouched_bit_for_bit() {
        let d = Vec3::new(-0.0, 1e30, -7.25);
        let i = Periodicity::NONE.image(d);
        assert_eq!(i.to_array().map(f32::to_bits), d.to_array().map(f32::to_bits));
        assert_eq!(unit_x().image(Vec3::new(0.1, 5.0, -5.0)), Vec3::new(0.1, 5.0, -5.0));
        assert_eq!(Periodicity::NONE.wrap(Vec3::splat(-9.0)), Vec3::splat(-9.0));
    }

    #[test]
    fn images_take_the_nearest_copy() {
        let p = unit_x();
        assert!((p.image(Vec3::new(0.9, 0.0, 0.0)).x + 0.1).abs() < 1e-6);
        assert!((p.image(Vec3::new(-0.9, 0.0, 0.0)).x - 0.1).abs() < 1e-6);
        assert_eq!(p.image(Vec3::new(0.4, 0.0, 0.0)).x, 0.4);
    }

    #[test]
    fn wrapping_lands_inside_the_period() {
        let p = unit_x();
        for x in [-2.5, -1.0, -1e-9, 0.0, 0.5, 1.0, 1.0 + 1e-7, 3.75] {
            let w = p.wrap(Vec3::new(x, 7.0, 8.0));
            assert!((0.0..1.0).contains(&w.x), "{x} -> {}", w.x);
            assert_eq!((w.y, w.z), (7.0, 8.0));
            let shift = (x - w.x) as f64;
            assert!((shift - shift.round()).abs() < 1e-6, "{x} moved by a whole period");
        }
    }
}
