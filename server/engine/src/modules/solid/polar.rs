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
/// `S^-1 = V diag(1 / sqrt(l)) V^T`, `R = A S^-1`; where `det A < 0` the axis of
/// the smallest eigenvalue is flipped, so `R` is a rotation, not a reflection.
/// Eigenvalues below `1e-12 * trace` are raised to it (a flat cluster).
pub fn eigen(a: Mat3) -> Quat {
    let (values, v) = symmetric_eigen(a.transpose() * a);
    let floor = 1e-12 * (values.x + values.y + values.z).max(1e-30);
    let mut inv = values.max(Vec3::splat(floor)).map(|l| 1.0 / l.sqrt());
    if a.determinant() < 0.0 {
        let smallest = if values.x <= values.y && values.x <= values.z {
            0
        } else if values.y <= values.z {
            1
        } else {
            2
        };
        inv[smallest] = -inv[smallest];
    }
    let r = a * v * Mat3::from_diagonal(inv) * v.transpose();
    Quat::from_mat3(&orthonormal(r)).normalize()
}

/// Gram-Schmidt on the columns (rounding leaves `R` a hair off orthonormal).
fn orthonormal(r: Mat3) -> Mat3 {
    let x = r.x_axis.normalize_or_zero();
    let y = (r.y_axis - x * x.dot(r.y_axis)).normalize_or_zero();
    Mat3::from_cols(x, y, x.cross(y))
}

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
}
