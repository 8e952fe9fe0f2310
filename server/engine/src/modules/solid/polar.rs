//! The rotation `R` of a cluster's moment matrix `A = sum m (x - c)(x0 - c0)^T`
//! (the first thesis's eqs. 2.14-2.18, after Mueller et al. 2005): its polar
//! decomposition `A = R S`, two ways ([`super::spec::Rotation`]).

use crate::math::{Mat3, Quat, Vec3};

/// Mueller, Bender, Chentanez and Macklin 2016, "A Robust Method to Extract the
/// Rotational Part of Deformations", alg. 1: from the rotation `q` (the cluster's
/// of the step before), turn by `omega = sum_i r_i x a_i / (|sum_i r_i . a_i| + eps)`
/// (`r_i`, `a_i` the columns of `R` and `A`) until the turn is negligible. Always a
/// rotation, also for flat or inverted clusters.
pub fn iterative(a: Mat3, mut q: Quat, iterations: u32) -> Quat {
    for _ in 0..iterations {
        let r = Mat3::from_quat(q);
        let cross = r.x_axis.cross(a.x_axis) + r.y_axis.cross(a.y_axis) + r.z_axis.cross(a.z_axis);
        let dot = r.x_axis.dot(a.x_axis) + r.y_axis.dot(a.y_axis) + r.z_axis.dot(a.z_axis);
        let omega = cross / (dot.abs() + 1e-9);
        let w = omega.length();
        if w < 1e-9 {
            break;
        }
        q = (Quat::from_axis_angle(omega / w, w) * q).normalize();
    }
    q
}

/// The first thesis's: `A^T A = V diag(l) V^T` (Jacobi eigenvalue rotations),
/// `R = A S^-1 = A V diag(1 / sqrt(l)) V^T`, written as `R = U V^T` with
/// `u_k = A v_k / sqrt(l_k)` for the two largest eigenvalues and the third axes
/// `u_0 x u_1`, `v_0 x v_1`: so `R` is a rotation where `det A < 0` (the thesis's
/// flip of the smallest axis) and also for a flat cluster (a thin feature's,
/// `l_2 = 0`: its `1 / sqrt(l_2)` would multiply rounding into the rotation). A
/// cluster on a line (the part of `A v_1` across `u_0` at most [`STRAIGHT`] of
/// `|A v_0|`) turns by the shortest arc from `v_0` to `u_0`; one on a point does
/// not turn. The line is told by `A`'s images, not by the eigenvalues: for a
/// cluster of two members `l_1` is rounding, which came out at 1.6e-8 of `l_0` on
/// a bunny's ear tip at 2 cm, and the normalised `u_1` of nothing was NaN.
pub fn eigen(a: Mat3) -> Quat {
    let (values, v) = symmetric_eigen(a.transpose() * a);
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| values[j].total_cmp(&values[i]));
    let (v0, v1) = (v.col(order[0]), v.col(order[1]));
    let av0 = a * v0;
    if av0 == Vec3::ZERO {
        return Quat::IDENTITY;
    }
    let u0 = av0.normalize();
    let av1 = a * v1;
    let across = av1 - u0 * u0.dot(av1);
    if across.length() <= STRAIGHT * av0.length() {
        return Quat::from_rotation_arc(v0, u0);
    }
    let u1 = across.normalize();
    let v1 = (v1 - v0 * v0.dot(v1)).normalize();
    let u = Mat3::from_cols(u0, u1, u0.cross(u1));
    let w = Mat3::from_cols(v0, v1, v0.cross(v1));
    Quat::from_mat3(&(u * w.transpose())).normalize()
}

/// Below this share of `|A v_0|` the image of a cluster's second axis is taken as
/// missing: the cluster is straight (its singular values' ratio; a lattice
/// cluster's thinnest is about a third, the rounding of a straight one's about
/// 1e-7).
pub const STRAIGHT: f32 = 1e-4;

/// Eigenvalues and eigenvectors (columns) of a symmetric 3x3 matrix by cyclic
/// Jacobi rotations.
fn symmetric_eigen(m: Mat3) -> (Vec3, Mat3) {
    let mut a = m.to_cols_array_2d();
    let mut v = [[1.0f32, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..16 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off < 1e-20 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q].abs() < 1e-30 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // a = J^T a J with J the rotation in the (p, q) plane (a is symmetric:
            // column and row indices alike).
            let turn = |x: &mut f32, y: &mut f32| (*x, *y) = (c * *x - s * *y, s * *x + c * *y);
            for row in a.iter_mut().chain(v.iter_mut()) {
                let (mut x, mut y) = (row[p], row[q]);
                turn(&mut x, &mut y);
                (row[p], row[q]) = (x, y);
            }
            let (low, high) = a.split_at_mut(q);
            for (x, y) in low[p].iter_mut().zip(high[0].iter_mut()) {
                turn(x, y);
            }
        }
    }
    // `v` holds the eigenvectors as columns in row-major order: transpose into glam.
    let vecs = Mat3::from_cols_array_2d(&v).transpose();
    (Vec3::new(a[0][0], a[1][1], a[2][2]), vecs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation times a stretch: both methods give the rotation back; a
    /// reflection comes out as a rotation.
    #[test]
    fn both_methods_find_the_rotation_of_a_stretch() {
        let r = Quat::from_euler(glam::EulerRot::XYZ, 0.4, -0.9, 1.3);
        let s = Mat3::from_cols(Vec3::new(1.5, 0.1, 0.0), Vec3::new(0.1, 0.8, 0.2), Vec3::new(0.0, 0.2, 1.1));
        let a = Mat3::from_quat(r) * s;
        let close = |q: Quat| q.angle_between(r) < 1e-4;
        assert!(close(eigen(a)), "eigen: {:?}", eigen(a));
        assert!(close(iterative(a, Quat::IDENTITY, 100)), "iterative: {:?}", iterative(a, Quat::IDENTITY, 100));
        let flipped = a * Mat3::from_diagonal(Vec3::new(1.0, 1.0, -1.0));
        for q in [eigen(flipped), iterative(flipped, Quat::IDENTITY, 100)] {
            assert!((Mat3::from_quat(q).determinant() - 1.0).abs() < 1e-5 && q.is_finite());
        }
    }

    /// A flat cluster (a plane of points, as in a bunny's ear one lattice layer
    /// thick) and a straight one (two points) turned by a rotation: the eigen
    /// method finds the rotation, not one skewed by the rounding of the missing
    /// direction.
    #[test]
    fn eigen_turns_flat_and_straight_clusters_right() {
        let r = Quat::from_euler(glam::EulerRot::XYZ, 0.3, 1.1, -0.7);
        let moment = |rest: &[Vec3]| {
            let c = rest.iter().sum::<Vec3>() / rest.len() as f32;
            rest.iter().fold(Mat3::ZERO, |a, &q| {
                let (q, x) = (q - c, r * (q - c));
                a + Mat3::from_cols(x * q.x, x * q.y, x * q.z)
            })
        };
        let s = 0.01;
        let plane: Vec<Vec3> =
            (0..9).map(|k| Vec3::new((k % 3) as f32 * s, (k / 3) as f32 * s, 0.0) + Vec3::splat(0.3)).collect();
        let q = eigen(moment(&plane));
        assert!(q.angle_between(r) < 1e-3, "plane: {:?} is {} rad off", q, q.angle_between(r));
        // A line fixes the rotation up to a turn about itself: its direction maps right.
        let line = [Vec3::splat(0.3), Vec3::new(0.3 + s, 0.3, 0.3)];
        let q = eigen(moment(&line));
        assert!((q * Vec3::X - r * Vec3::X).length() < 1e-4, "line: {:?}", q * Vec3::X);
        assert_eq!(eigen(Mat3::ZERO), Quat::IDENTITY);
    }

    /// A cluster of two members whose second eigenvalue is rounding 1.6e-8 of the
    /// first (the moment of a bunny's ear tip at 2 cm, as a step left it): a
    /// rotation, not NaN, that takes the pair's rest direction to its current one.
    #[test]
    fn a_straight_cluster_with_rounding_across_it_turns_by_its_arc() {
        let a = Mat3::from_cols(
            Vec3::new(0.00019982975, -2.1159629e-8, -0.000200168),
            Vec3::ZERO,
            Vec3::new(-0.00019983004, 2.115966e-8, 0.0002001683),
        );
        let q = eigen(a);
        assert!(q.is_finite() && (q.length() - 1.0).abs() < 1e-6, "{q:?}");
        let rest = Vec3::new(1.0, 0.0, -1.0).normalize();
        let now = Vec3::new(0.00019982975, -2.1159629e-8, -0.000200168).normalize();
        assert!((q * rest).distance(now) < 1e-3 || (q * rest).distance(-now) < 1e-3, "{:?}", q * rest);
    }
}
