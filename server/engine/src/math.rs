//! Numeric types shared by the whole engine.
//!
//! Particle state is `f32` (what a GPU holds natively, and half the memory
//! traffic of `f64`); sums over many particles that feed reports use `f64`.

/// Scalar type of per-particle state. SI units everywhere (m, s, kg, Pa).
pub type Real = f32;

/// 3-vector of per-particle state (12 bytes, no padding: memory per particle matters).
pub type Vec3 = glam::Vec3;
/// A 3x3 matrix (column-major).
pub type Mat3 = glam::Mat3;
/// A rotation (unit quaternion, x y z w, w the scalar part).
pub type Quat = glam::Quat;

/// Axis-aligned box in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower corner (m).
    pub min: Vec3,
    /// Upper corner (m).
    pub max: Vec3,
}

impl Aabb {
    /// Box from two corners.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb::new(self.min.min(other.min), self.max.max(other.max))
    }

    /// The box grown by `margin` on every side.
    pub fn expanded(self, margin: Real) -> Aabb {
        Aabb::new(self.min - Vec3::splat(margin), self.max + Vec3::splat(margin))
    }

    /// Edge lengths (m).
    pub fn size(self) -> Vec3 {
        self.max - self.min
    }

    /// Whether `p` lies inside (boundary included).
    pub fn contains(self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}
