//! SPH smoothing kernels, all parametrised by their support radius `h` (m):
//! `W(r) = 0` for `r >= h`.
//!
//! Three families, selectable per scene (`solver.kernel`):
//! - [`KernelKind::Mueller`]: Müller, Charypar & Gross 2003, "Particle-based fluid
//!   simulation for interactive applications" (SCA 2003): poly6 for density (eq. 20),
//!   the spiky gradient for pressure (eq. 21) and the viscosity-kernel Laplacian
//!   (eq. 22) for viscosity.
//! - [`KernelKind::CubicSpline`]: Monaghan's M4 cubic B-spline (Monaghan 1992,
//!   Annu. Rev. Astron. Astrophys. 30, eq. 2.6) normalised in 3D for support `h`
//!   (as in SPlisHSPlasH); its Laplacian uses Brookshaw's approximation
//!   `lap = -2 W'(r) r / (r^2 + 0.01 h^2)` (Brookshaw 1985; Morris, Fox & Zhu 1997,
//!   eq. 8, with their regularisation of `-2 W'(r) / r` at small r).
//! - [`KernelKind::WendlandC2`]: Wendland's C2 function (Wendland 1995, Adv. Comput.
//!   Math. 4; in 3D as Dehnen & Aly 2012, MNRAS 425, table 1:
//!   `W = 21 / (2 pi h^3) (1 - q)^4 (1 + 4q)`, `q = r / h`), the cubic spline's
//!   Laplacian; its gradient is scaled so that its moment on the scene's lattice is
//!   exact ([`Kernel::on_lattice`]), so it is then 1/0.950 of `W`'s derivative at 2
//!   spacings. Wendland's functions have a non-negative Fourier transform and avoid the
//!   pairing instability at any neighbour number (Dehnen & Aly 2012): DFSPH's resting
//!   column keeps its lattice on it, where on the cubic spline its particles leave
//!   their layers by a tenth to a third of a spacing (docs/validation/schemes/CG.md).

use crate::math::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::f32::consts::PI;

/// Which kernel family a scene uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum KernelKind {
    /// Poly6 density, spiky pressure gradient, viscosity-kernel Laplacian (Müller et al. 2003).
    /// Needs more artificial viscosity (alpha ~0.1) to stay quiet: poly6 and the
    /// spiky gradient are not derived from one kernel, which feeds particle noise.
    Mueller,
    /// Cubic B-spline for density and gradients, Brookshaw Laplacian. The default:
    /// consistent kernel and gradient, quietest with little viscosity.
    #[default]
    CubicSpline,
    /// Wendland's C2 function with a lattice-exact gradient, Brookshaw Laplacian.
    WendlandC2,
}

/// A kernel with its constants precomputed for one support radius.
#[derive(Debug, Clone, Copy)]
pub struct Kernel {
    kind: KernelKind,
    h: Real,
    h2: Real,
    inv_h: Real,
    /// Normalisation of `W` (poly6: 315/(64 pi h^9); cubic: 8/(pi h^3); Wendland:
    /// 21/(2 pi h^3)).
    w_norm: Real,
    /// Normalisation of `|grad W|` (spiky: 45/(pi h^6); cubic: 48/(pi h^4);
    /// Wendland: 210/(pi h^4), over its lattice moment once [`Kernel::on_lattice`]
    /// scaled it).
    g_norm: Real,
}

impl Kernel {
    /// Kernel of family `kind` with support radius `h` (m).
    pub fn new(kind: KernelKind, h: Real) -> Self {
        let (w_norm, g_norm) = match kind {
            KernelKind::Mueller => (315.0 / (64.0 * PI * h.powi(9)), 45.0 / (PI * h.powi(6))),
            KernelKind::CubicSpline => (8.0 / (PI * h.powi(3)), 48.0 / (PI * h.powi(4))),
            KernelKind::WendlandC2 => (21.0 / (2.0 * PI * h.powi(3)), 210.0 / (PI * h.powi(4))),
        };
        Self { kind, h, h2: h * h, inv_h: 1.0 / h, w_norm, g_norm }
    }

    /// The kernel a scene of particle `spacing` (m) uses: Wendland's gradient
    /// divided by its moment on the lattice, `-sum_j V_j y_j^2 (dW/dr)(r_j) / r_j`
    /// with `V = 1 / sum_j W` the volume the particle mass implies, which is then 1.
    /// At a support of 2 spacings the moment is 0.950: a pressure gradient 5 % short
    /// that DFSPH's resting column answered with a pressure 5.8 % high everywhere.
    /// The other families are left as they are (the cubic spline's moment is 1.020 at
    /// 2 spacings and 1.008 at 3; every preset's validation predates this scaling).
    pub fn on_lattice(kind: KernelKind, h: Real, spacing: Real) -> Self {
        let k = Self::new(kind, h);
        match kind {
            KernelKind::WendlandC2 => Self { g_norm: k.g_norm / k.lattice_gradient_moment(spacing), ..k },
            KernelKind::Mueller | KernelKind::CubicSpline => k,
        }
    }

    /// `-sum_j V_j y_j^2 (dW/dr)(r_j) / r_j` over the lattice of `spacing`, `V = 1 /
    /// sum_j W`: 1 for a gradient exact for a linear field on that lattice.
    pub fn lattice_gradient_moment(&self, spacing: Real) -> Real {
        -self.lattice_sum_of(spacing, |volume, x, r| volume * x.y * x.y * self.dw_dr(r) / r) as Real
    }

    /// Support radius (m).
    pub fn support(&self) -> Real {
        self.h
    }

    /// The normalisations of `W` and of `|grad W|` (see the fields), for
    /// backends that evaluate the kernel themselves.
    pub fn norms(&self) -> (Real, Real) {
        (self.w_norm, self.g_norm)
    }

    /// The family.
    pub fn kind(&self) -> KernelKind {
        self.kind
    }

    /// `W` from the squared distance `r2` (1/m^3). Poly6 needs no square root.
    #[inline(always)]
    pub fn w_r2(&self, r2: Real) -> Real {
        if r2 >= self.h2 {
            return 0.0;
        }
        match self.kind {
            KernelKind::Mueller => {
                let d = self.h2 - r2;
                self.w_norm * d * d * d
            }
            KernelKind::CubicSpline => self.cubic(r2.sqrt() * self.inv_h),
            KernelKind::WendlandC2 => {
                let q = r2.sqrt() * self.inv_h;
                let t = 1.0 - q;
                self.w_norm * t * t * t * t * (1.0 + 4.0 * q)
            }
        }
    }

    /// Both branches are computed and one selected: inside the support the
    /// `q <= 0.5` test is a coin flip per neighbour, and a select beats a mispredict.
    #[inline(always)]
    fn cubic(&self, q: Real) -> Real {
        let inner = 6.0 * q * q * (q - 1.0) + 1.0;
        let t = 1.0 - q;
        let outer = 2.0 * t * t * t;
        self.w_norm * if q <= 0.5 { inner } else { outer }
    }

    /// `dW/dr` at distance `r` (m), which is <= 0. For the Müller family this is the
    /// spiky kernel's derivative (used for pressure gradients, eq. 21).
    #[inline(always)]
    pub fn dw_dr(&self, r: Real) -> Real {
        if r >= self.h {
            return 0.0;
        }
        match self.kind {
            KernelKind::Mueller => {
                let d = self.h - r;
                -self.g_norm * d * d
            }
            KernelKind::CubicSpline => {
                let q = r * self.inv_h;
                let inner = q * (3.0 * q - 2.0);
                let t = 1.0 - q;
                let outer = -t * t;
                self.g_norm * if q <= 0.5 { inner } else { outer }
            }
            KernelKind::WendlandC2 => {
                let q = r * self.inv_h;
                let t = 1.0 - q;
                -self.g_norm * q * t * t * t
            }
        }
    }

    /// The packing of this kernel's `dW/dr / r` into 16 bits ([`GradientPacking`]);
    /// none for the Müller family, whose spiky `dW/dr / r` grows without bound as
    /// `r -> 0`.
    pub fn gradient_packing(&self) -> Option<GradientPacking> {
        // The largest size of dW/dr / r, at q = 0 for both: g_norm (3q - 2) / h for the
        // cubic spline's q <= 1/2, -g_norm (1 - q)^3 / h for Wendland's.
        let max = match self.kind {
            KernelKind::Mueller => return None,
            KernelKind::CubicSpline => 2.0 * self.g_norm * self.inv_h,
            KernelKind::WendlandC2 => self.g_norm * self.inv_h,
        };
        Some(GradientPacking { to_unit: Real::from(u16::MAX) / max, from_unit: max / Real::from(u16::MAX) })
    }

    /// Gradient of `W` with respect to `x_i` for `x_ij = x_i - x_j` at distance `r`.
    #[inline(always)]
    pub fn grad(&self, x_ij: Vec3, r: Real) -> Vec3 {
        if r <= 1e-9 * self.h {
            return Vec3::ZERO;
        }
        x_ij * (self.dw_dr(r) / r)
    }

    /// Laplacian weight `L(r) >= 0` such that `lap A_i = sum_j V_j (A_j - A_i) L(r_ij)`.
    /// Müller: the viscosity kernel's Laplacian `45/(pi h^6) (h - r)` (eq. 22).
    /// Cubic: Brookshaw's `-2 W'(r) / r`, regularised by `0.01 h^2` as in Morris et al.
    #[inline(always)]
    pub fn laplacian(&self, r: Real) -> Real {
        if r >= self.h {
            return 0.0;
        }
        match self.kind {
            KernelKind::Mueller => self.g_norm * (self.h - r),
            KernelKind::CubicSpline | KernelKind::WendlandC2 => -2.0 * self.dw_dr(r) * r / (r * r + 0.01 * self.h2),
        }
    }

    /// `F = x_ij . grad_i W_ij / (r^2 + eps_h2)` at distance `r` (1/m^5 with the
    /// kernel's 1/m^3; never positive): the pair factor of the SPH Laplacians of
    /// Cleary & Monaghan (1999, conduction) and Morris, Fox & Zhu (1997, viscosity),
    /// whose weight is `-2 F`. Their passes take `eps_h2 = 0.01 h^2`, h half the support.
    #[inline(always)]
    pub fn pair_factor(&self, r: Real, eps_h2: Real) -> Real {
        r * self.dw_dr(r) / (r * r + eps_h2)
    }

    /// [`Self::lattice_laplacian_scale`] of the pair Laplacian `-2 F` (see
    /// [`Self::pair_factor`]) on the lattice of `spacing`: the normalisation of
    /// conduction and of the per-particle viscous force.
    pub fn pair_lattice_scale(&self, spacing: Real) -> Real {
        let eps_h2 = 0.0025 * self.h2;
        self.lattice_laplacian_scale(spacing, |r| -2.0 * self.pair_factor(r, eps_h2))
    }

    /// The factor `s` that makes a Laplacian weight exact on the particle lattice:
    /// with `lap A_i = s sum_j V_j (A_j - A_i) L(r_ij)`, `s = 6 / sum_j V_j r_j^2 L(r_j)`
    /// gives `lap x^2 = 2` on the full lattice of `spacing` at rest, `V_j = 1 / sum W`
    /// the volume the particle mass implies. With a support of a few spacings the
    /// lattice sum misses the Laplacian by a fixed fraction (about 1 % for the cubic
    /// spline at two spacings) that refinement at a fixed support ratio never removes;
    /// `s` divides it out, as the particle mass divides out the lattice's kernel sum.
    pub fn lattice_laplacian_scale(&self, spacing: Real, weight: impl Fn(Real) -> Real) -> Real {
        (6.0 / self.lattice_sum_of(spacing, |volume, _, r| volume * r * r * weight(r))) as Real
    }

    /// `sum_j f(V, x_j, r_j)` over the neighbours `x_j` of a particle of the lattice of
    /// `spacing` within the support, `V = 1 / sum_j W` the volume the particle mass
    /// implies (each term in f32, summed in f64).
    fn lattice_sum_of(&self, spacing: Real, f: impl Fn(Real, Vec3, Real) -> Real) -> f64 {
        let volume = 1.0 / crate::boundary::lattice_sum(self, spacing, None);
        let reach = (self.h / spacing).ceil() as i32;
        let mut sum = 0.0f64;
        for k in -reach..=reach {
            for j in -reach..=reach {
                for i in -reach..=reach {
                    let x = Vec3::new(i as Real, j as Real, k as Real) * spacing;
                    let r = x.length();
                    if r > 0.0 && r < self.h {
                        sum += f64::from(f(volume, x, r));
                    }
                }
            }
        }
        sum
    }
}

/// A pair's kernel gradient in 16 bits: `dW/dr / r` (never positive) as a fraction
/// of its largest size, an absolute error of at most 1/131070 of it (4e-6 of the
/// largest slope's, a few 1e-5 of a neighbour's at one spacing). The gradient is the
/// separation times it, so a pair costs 2 bytes where a kept gradient costs 12.
#[derive(Debug, Clone, Copy)]
pub struct GradientPacking {
    to_unit: Real,
    from_unit: Real,
}

impl GradientPacking {
    /// `x_ij`'s `dW/dr / r` packed (0 where the particles coincide).
    #[inline(always)]
    pub fn pack(&self, k: &Kernel, x_ij: Vec3) -> u16 {
        let r = x_ij.length();
        let f = if r > 0.0 { k.dw_dr(r) / r } else { 0.0 };
        (-f * self.to_unit).round().clamp(0.0, Real::from(u16::MAX)) as u16
    }

    /// `dW/dr / r` of a packed value (1/m^5).
    #[inline(always)]
    pub fn unpack(&self, packed: u16) -> Real {
        -Real::from(packed) * self.from_unit
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates `f` over a cube holding the support with a midpoint rule in f64.
    fn integrate(h: Real, n: i32, f: impl Fn(Vec3) -> f64) -> f64 {
        let step = 2.0 * h as f64 / n as f64;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let c = |a: i32| (-(h as f64) + (a as f64 + 0.5) * step) as f32;
                    sum += f(Vec3::new(c(i), c(j), c(k)));
                }
            }
        }
        sum * step * step * step
    }

    #[test]
    fn the_lattice_laplacian_scale_is_about_one_per_cent_for_the_cubic_spline() {
        let spacing = 0.01;
        let k = Kernel::new(KernelKind::CubicSpline, 2.0 * spacing);
        let s = k.lattice_laplacian_scale(spacing, |r| k.laplacian(r));
        assert!((0.003..0.02).contains(&(s - 1.0).abs()), "{s}");
        // A finer lattice at the same support ratio needs the same factor.
        let fine = Kernel::new(KernelKind::CubicSpline, 0.2 * spacing);
        assert!((fine.lattice_laplacian_scale(0.1 * spacing, |r| fine.laplacian(r)) - s).abs() < 1e-5);
    }

    #[test]
    fn packed_gradients_are_within_their_bound_of_the_gradient() {
        for (kind, largest) in [(KernelKind::CubicSpline, 2.0), (KernelKind::WendlandC2, 1.0)] {
            let k = Kernel::on_lattice(kind, 0.02, 0.01);
            let p = k.gradient_packing().expect("the kernel packs");
            let max = largest * k.g_norm / 0.02;
            for i in 0..=1000 {
                let x = Vec3::new(0.6, -0.8, 0.0) * (0.02 * i as Real / 1000.0);
                let r = x.length();
                let exact = k.grad(x, r);
                let packed = x * p.unpack(p.pack(&k, x));
                assert!((packed - exact).length() <= r * max / 131_000.0 + 1e-6 * exact.length(), "{kind:?} r={r}");
                // The largest size is the one at r = 0, and nothing is clamped.
                assert!(exact.length() <= r * max * (1.0 + 1e-6), "{kind:?} r={r}");
            }
            assert_eq!(p.pack(&k, Vec3::ZERO), 0);
        }
        assert!(Kernel::new(KernelKind::Mueller, 0.02).gradient_packing().is_none());
    }

    #[test]
    fn wendlands_gradient_is_exact_on_its_lattice_and_the_others_are_left_alone() {
        let spacing = 0.01;
        let raw = Kernel::new(KernelKind::WendlandC2, 2.0 * spacing).lattice_gradient_moment(spacing);
        assert!((raw - 0.950).abs() < 2e-3, "{raw}");
        for support in [2.0, 2.5, 3.0] {
            let k = Kernel::on_lattice(KernelKind::WendlandC2, support * spacing, spacing);
            assert!((k.lattice_gradient_moment(spacing) - 1.0).abs() < 1e-5, "support {support}");
            // The same scaling at the same support ratio on a finer lattice.
            let fine = Kernel::on_lattice(KernelKind::WendlandC2, support * 0.1 * spacing, 0.1 * spacing);
            assert!((fine.g_norm * 0.1f32.powi(4) / k.g_norm - 1.0).abs() < 1e-4, "support {support}");
        }
        let cubic = Kernel::on_lattice(KernelKind::CubicSpline, 2.0 * spacing, spacing);
        assert!((cubic.lattice_gradient_moment(spacing) - 1.020).abs() < 2e-3);
        assert_eq!(cubic.g_norm, Kernel::new(KernelKind::CubicSpline, 2.0 * spacing).g_norm);
    }

    #[test]
    fn kernels_integrate_to_one() {
        for kind in [KernelKind::Mueller, KernelKind::CubicSpline, KernelKind::WendlandC2] {
            let k = Kernel::new(kind, 0.1);
            let total = integrate(0.1, 80, |x| k.w_r2(x.length_squared()) as f64);
            assert!((total - 1.0).abs() < 2e-3, "{kind:?} integrates to {total}");
        }
    }

    #[test]
    fn spiky_gradient_is_the_derivative_of_a_normalised_kernel() {
        // The spiky kernel W = 15/(pi h^6) (h - r)^3 integrates to one; check that
        // its radial derivative matches what `dw_dr` returns, by finite differences.
        let h = 0.1;
        let k = Kernel::new(KernelKind::Mueller, h);
        let spiky = |r: f32| 15.0 / (PI * h.powi(6)) * (h - r).powi(3);
        for r in [0.01, 0.03, 0.05, 0.08] {
            let fd = (spiky(r + 1e-4) - spiky(r - 1e-4)) / 2e-4;
            assert!((fd - k.dw_dr(r)).abs() < 1e-2 * k.dw_dr(r).abs(), "r={r}");
        }
        for kind in [KernelKind::CubicSpline, KernelKind::WendlandC2] {
            let c = Kernel::new(kind, h);
            for r in [0.01, 0.03, 0.06, 0.08] {
                let fd = (c.w_r2((r + 1e-4) * (r + 1e-4)) - c.w_r2((r - 1e-4) * (r - 1e-4))) / 2e-4;
                assert!((fd - c.dw_dr(r)).abs() < 1e-2 * c.dw_dr(r).abs().max(1.0), "{kind:?} r={r}");
            }
        }
    }

    #[test]
    fn gradient_is_antisymmetric_and_points_inward() {
        for kind in [KernelKind::Mueller, KernelKind::CubicSpline, KernelKind::WendlandC2] {
            let k = Kernel::new(kind, 0.1);
            let x = Vec3::new(0.02, -0.03, 0.01);
            let r = x.length();
            let g_ij = k.grad(x, r);
            let g_ji = k.grad(-x, r);
            assert_eq!(g_ij, -g_ji, "{kind:?}");
            assert!(g_ij.dot(x) < 0.0, "{kind:?}: gradient must point towards j");
            assert_eq!(k.grad(Vec3::ZERO, 0.0), Vec3::ZERO);
        }
    }

    #[test]
    fn laplacian_weights_are_positive_inside_and_zero_outside() {
        for kind in [KernelKind::Mueller, KernelKind::CubicSpline, KernelKind::WendlandC2] {
            let k = Kernel::new(kind, 0.1);
            for r in [0.001, 0.03, 0.07, 0.099] {
                assert!(k.laplacian(r) > 0.0, "{kind:?} r={r}");
            }
            assert_eq!(k.laplacian(0.1), 0.0);
            assert_eq!(k.w_r2(0.011), 0.0);
        }
    }
}
