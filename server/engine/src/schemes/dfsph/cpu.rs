//! DFSPH's passes on the CPU, over the step's neighbour lists (the formulas are in
//! the scheme's documentation; the GPU's kernels add the same terms in the same
//! order).
//!
//! The factor pass keeps every pair's kernel gradient beside the neighbour rows
//! ([`crate::cpu::neighbors::ChunkNeighbors::keep`]) and the solves' passes read them
//! back: the positions do not move between the factor and the drift, and a step
//! iterates each solve several times (about 9 iterations of two passes per step on
//! the dam break), so the kernel is evaluated once instead of once per pass. Whole
//! gradients cost 12 bytes a pair; with `solver.dfsph.compact_gradients` each pair
//! keeps its `dW/dr / r` in 2 bytes ([`GradientPacking`]) and the passes multiply it
//! by the separation: half the memory (365-378 against 742-762 bytes a particle at
//! 1M) at 1.1 (1M particles) to 1.4 (21,952) times the step's time
//! (docs/benchmarks.md). The factor reads the kept values too, so its diagonal is
//! that of the system the kicks apply.

use super::{DfsphConsts, FULL_NEIGHBOURHOOD, WARM_START};
use crate::attrs::Attrs;
use crate::cpu::neighbors::{CHUNK, ChunkNeighbors, PairValue};
use crate::cpu::{CpuCx, CpuPass};
use crate::kernel::{GradientPacking, Kernel};
use crate::math::{Real, Vec3};
use crate::model::Model;
use crate::periodic::Separation;
use rayon::prelude::*;

/// What the factor pass keeps of each pair for the solves' passes.
pub(super) trait Kept: Copy + Sync {
    /// The value kept per pair.
    type Value: PairValue + Send + Sync;
    /// The value for the separation `x_ij`.
    fn keep(&self, x_ij: Vec3) -> Self::Value;
    /// The pair's `grad_i W` from its kept value and, where the value needs it, its
    /// separation (`x_ij` is not called otherwise, so its positions are not read).
    fn gradient(&self, kept: Self::Value, x_ij: impl FnOnce() -> Vec3) -> Vec3;
    /// `s grad_i W`, the scalar applied before the vector where that saves work.
    fn scaled(&self, kept: Self::Value, x_ij: impl FnOnce() -> Vec3, s: Real) -> Vec3;
    /// `w . grad_i W`.
    fn dot(&self, kept: Self::Value, x_ij: impl FnOnce() -> Vec3, w: Vec3) -> Real;
}

/// Whole gradients (12 bytes a pair).
#[derive(Clone, Copy)]
pub(super) struct Whole<'a>(pub(super) &'a Kernel);

impl Kept for Whole<'_> {
    type Value = Vec3;
    #[inline(always)]
    fn keep(&self, x: Vec3) -> Vec3 {
        // Zero for coinciding particles, as in the forces.
        let r2 = x.length_squared();
        if r2 == 0.0 {
            return Vec3::ZERO;
        }
        let r = r2.sqrt();
        x * (self.0.dw_dr(r) / r)
    }
    #[inline(always)]
    fn gradient(&self, kept: Vec3, _: impl FnOnce() -> Vec3) -> Vec3 {
        kept
    }
    #[inline(always)]
    fn scaled(&self, kept: Vec3, _: impl FnOnce() -> Vec3, s: Real) -> Vec3 {
        kept * s
    }
    #[inline(always)]
    fn dot(&self, kept: Vec3, _: impl FnOnce() -> Vec3, w: Vec3) -> Real {
        w.dot(kept)
    }
}

/// Packed `dW/dr / r` (2 bytes a pair).
#[derive(Clone, Copy)]
pub(super) struct Packed<'a>(pub(super) &'a Kernel, pub(super) GradientPacking);

impl Kept for Packed<'_> {
    type Value = u16;
    #[inline(always)]
    fn keep(&self, x: Vec3) -> u16 {
        self.1.pack(self.0, x)
    }
    #[inline(always)]
    fn gradient(&self, kept: u16, x_ij: impl FnOnce() -> Vec3) -> Vec3 {
        x_ij() * self.1.unpack(kept)
    }
    #[inline(always)]
    fn scaled(&self, kept: u16, x_ij: impl FnOnce() -> Vec3, s: Real) -> Vec3 {
        x_ij() * (self.1.unpack(kept) * s)
    }
    #[inline(always)]
    fn dot(&self, kept: u16, x_ij: impl FnOnce() -> Vec3, w: Vec3) -> Real {
        self.1.unpack(kept) * w.dot(x_ij())
    }
}

/// Runs `$body` with `$kept` the model's [`Kept`] and `$sep` its separation.
macro_rules! with_kept {
    ($model:expr, |$kept:ident, $sep:ident| $body:expr) => {{
        let model: &crate::model::Model = $model;
        let compact = model.consts::<crate::schemes::dfsph::DfsphConsts>().settings.compact_gradients;
        match model.kernel.gradient_packing().filter(|_| compact) {
            Some(p) => {
                let $kept = crate::schemes::dfsph::cpu::Packed(&model.kernel, p);
                crate::with_separation!(&model.periodic, |$sep| $body)
            }
            None => {
                let $kept = crate::schemes::dfsph::cpu::Whole(&model.kernel);
                crate::with_separation!(&model.periodic, |$sep| $body)
            }
        }
    }};
}
pub(super) use with_kept;

/// Neighbours of slot `n` of a chunk (fluid and wall, the particle itself not
/// counted), against [`FULL_NEIGHBOURHOOD`].
#[inline(always)]
pub(super) fn neighbours(nb: &ChunkNeighbors, n: usize) -> u32 {
    (nb.fluid(n).len() - 1 + nb.walls(n).len()) as u32
}

/// The mass every material's particles have, if they have one.
fn uniform_mass(materials: &crate::materials::Materials) -> Option<Real> {
    let m = materials.get(0).mass;
    materials.iter().all(|x| x.mass == m).then_some(m)
}

/// What the solves' pair sums read: the positions, materials and walls, the kept
/// gradients and the walls' factor `c` (1 for Akinci's walls, 2 mirrored).
pub(super) struct Sums<'a, K, S> {
    kept: K,
    sep: S,
    model: &'a Model,
    pos: &'a [Vec3],
    mat: Option<&'a [u32]>,
    /// The particles' one mass where every material has it: the pair's
    /// `m_j^2 / m_i` is then `m` and the pair reads no material.
    uniform: Option<Real>,
    c: Real,
}

impl<'a, K: Kept, S: Separation> Sums<'a, K, S> {
    pub(super) fn new(model: &'a Model, attrs: &'a Attrs, kept: K, sep: S) -> Self {
        Self {
            kept,
            sep,
            model,
            pos: attrs.get(attrs.handle::<Vec3>("x")),
            mat: attrs.find::<u32>("material").map(|m| attrs.get(m)),
            uniform: uniform_mass(&model.materials),
            c: model.consts::<DfsphConsts>().wall_factor,
        }
    }

    /// `x_a - x_b` (across a periodic domain's seams).
    #[inline(always)]
    pub(super) fn separation(&self, a: Vec3, b: Vec3) -> Vec3 {
        self.sep.between(a, b)
    }

    /// Particle `i`'s material.
    #[inline(always)]
    pub(super) fn material(&self, i: usize) -> &'a crate::materials::Material {
        self.model.materials.get(self.mat.map_or(0, |m| m[i] as usize))
    }

    /// `(G P)_i = sum_j (m_i P_i + m_j^2 P_j / m_i) grad W_ij + c P_i sum_b psi_b grad W_ib`
    /// for particle `i` in slot `n` of its chunk `nb`.
    #[inline(always)]
    pub(super) fn gradient(&self, i: usize, n: usize, nb: &ChunkNeighbors, p: &[Real]) -> Vec3 {
        let (walls, xi) = (&self.model.wall_particles, self.pos[i]);
        let m_i = self.material(i).mass;
        let own = m_i * p[i];
        let mut a = Vec3::ZERO;
        for (&j, &v) in nb.fluid(n).iter().zip(nb.fluid_kept::<K::Value>(n)) {
            let j = j as usize;
            let m_j2 = self.uniform.unwrap_or_else(|| {
                let m_j = self.material(j).mass;
                m_j * m_j / m_i
            });
            a += self.kept.scaled(v, || self.sep.between(xi, self.pos[j]), own + m_j2 * p[j]);
        }
        let psi = &walls.psi[self.mat.map_or(0, |m| m[i] as usize)];
        let mut wall = Vec3::ZERO;
        for (&b, &v) in nb.walls(n).iter().zip(nb.wall_kept::<K::Value>(n)) {
            wall += self.kept.scaled(v, || self.sep.between(xi, walls.positions[b as usize]), psi[b as usize]);
        }
        a + wall * (self.c * p[i])
    }

    /// `sum_j V_j grad W_ij + sum_b V_b grad W_ib` (1/m) with the rest volumes
    /// `V_j = m_j / rho0_j` and the walls' `V_b = psi_b / rho0_i`: zero in a full
    /// neighbourhood, whatever its compression, and of the order of `1 / support` where
    /// the neighbourhood is cut by a free surface.
    #[inline(always)]
    pub(super) fn volume_gradient(&self, i: usize, n: usize, nb: &ChunkNeighbors) -> Vec3 {
        let (walls, xi) = (&self.model.wall_particles, self.pos[i]);
        let mut fluid = Vec3::ZERO;
        for (&j, &v) in nb.fluid(n).iter().zip(nb.fluid_kept::<K::Value>(n)) {
            let m = self.material(j as usize);
            fluid += self.kept.scaled(v, || self.sep.between(xi, self.pos[j as usize]), m.mass / m.rest_density);
        }
        let psi = &walls.psi[self.mat.map_or(0, |m| m[i] as usize)];
        let mut wall = Vec3::ZERO;
        for (&b, &v) in nb.walls(n).iter().zip(nb.wall_kept::<K::Value>(n)) {
            wall += self.kept.scaled(v, || self.sep.between(xi, walls.positions[b as usize]), psi[b as usize]);
        }
        fluid + wall / self.material(i).rest_density
    }

    /// `(D w)_i = m_i sum_j (w_i - w_j) . grad W_ij + c sum_b psi_b w_i . grad W_ib`:
    /// the compression rate (kg/(m^3 s)) of the velocities `w`.
    #[inline(always)]
    pub(super) fn divergence(&self, i: usize, n: usize, nb: &ChunkNeighbors, w: &[Vec3]) -> Real {
        let (walls, xi, wi) = (&self.model.wall_particles, self.pos[i], w[i]);
        let mut fluid = 0.0;
        for (&j, &v) in nb.fluid(n).iter().zip(nb.fluid_kept::<K::Value>(n)) {
            let j = j as usize;
            fluid += self.kept.dot(v, || self.sep.between(xi, self.pos[j]), wi - w[j]);
        }
        let psi = &walls.psi[self.mat.map_or(0, |m| m[i] as usize)];
        let mut wall = 0.0;
        for (&b, &v) in nb.walls(n).iter().zip(nb.wall_kept::<K::Value>(n)) {
            wall += psi[b as usize] * self.kept.dot(v, || self.sep.between(xi, walls.positions[b as usize]), wi);
        }
        self.material(i).mass * fluid + self.c * wall
    }
}

/// `alpha = 1 / (s . t + m_i^2 sum_j (m_i / m_j) |grad W_ij|^2)`, 0 for a particle
/// without neighbours.
#[derive(Debug)]
pub struct Factor;

impl CpuPass for Factor {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| factor(cx, kept, sep))
    }
}

fn factor<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let model = cx.model;
    let (walls, materials) = (&model.wall_particles, &model.materials);
    let h = cx.attrs.handle::<Real>("alpha");
    let mut alpha = cx.attrs.take(h);
    let attrs = &*cx.attrs;
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    let wall_factor = model.consts::<DfsphConsts>().wall_factor;
    alpha.par_chunks_mut(CHUNK).zip(cx.nb.chunks.par_iter_mut()).enumerate().for_each(|(c, (out, nb))| {
        nb.keep(
            |n, j| kept.keep(sep.between(pos[c * CHUNK + n], pos[j])),
            |n, b| kept.keep(sep.between(pos[c * CHUNK + n], walls.positions[b])),
        );
        for (n, a) in out.iter_mut().enumerate() {
            let (xi, mi) = (pos[c * CHUNK + n], material(c * CHUNK + n));
            let m_i = materials.get(mi).mass;
            let (mut fluid, mut sq) = (Vec3::ZERO, 0.0);
            for (&j, &v) in nb.fluid(n).iter().zip(nb.fluid_kept::<K::Value>(n)) {
                let g = kept.gradient(v, || sep.between(xi, pos[j as usize]));
                fluid += g * m_i;
                sq += g.length_squared() * (m_i / materials.get(material(j as usize)).mass);
            }
            let psi = &walls.psi[mi];
            let mut wall = Vec3::ZERO;
            for (&b, &v) in nb.walls(n).iter().zip(nb.wall_kept::<K::Value>(n)) {
                wall += kept.gradient(v, || sep.between(xi, walls.positions[b as usize])) * psi[b as usize];
            }
            let d = (fluid + wall * wall_factor).length_squared() + m_i * m_i * sq;
            *a = if d > 0.0 { 1.0 / d } else { 0.0 };
        }
    });
    cx.attrs.put(h, alpha);
}

/// A solve's warm start: `increment = WARM_START kappa`, `kappa = 0` (the kick that
/// follows adds the increment back).
#[derive(Debug)]
pub struct Warm {
    /// The stiffness attribute.
    pub kappa: &'static str,
    /// The increment attribute.
    pub increment: &'static str,
}

impl CpuPass for Warm {
    fn run(&self, cx: &mut CpuCx<'_>) {
        self.start(cx, WARM_START, None);
    }
}

impl Warm {
    /// `increment = w kappa` (0 where the attribute `held` is 1, if given),
    /// `kappa = 0`.
    pub(super) fn start(&self, cx: &mut CpuCx<'_>, w: Real, held: Option<&'static str>) {
        let (kh, dh) = (cx.attrs.handle::<Real>(self.kappa), cx.attrs.handle::<Real>(self.increment));
        let (mut kappa, mut inc) = (cx.attrs.take(kh), cx.attrs.take(dh));
        let held = held.map(|h| cx.attrs.get(cx.attrs.handle::<Real>(h)));
        kappa.par_iter_mut().zip(inc.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (k, d))| {
            *d = held.map_or(w, |h| w * (1.0 - h[i])) * *k;
            *k = 0.0;
        });
        cx.attrs.put(kh, kappa);
        cx.attrs.put(dh, inc);
    }
}

/// `v_i -= dt (sum_j (m_i dP_i + m_j^2 dP_j / m_i) grad W_ij + dP_i sum_b psi_b grad W_ib)`:
/// the pressure force of the increments `dP` of one solve, which are added to its
/// stiffness.
#[derive(Debug)]
pub struct Kick {
    /// The stiffness attribute.
    pub kappa: &'static str,
    /// The increment attribute.
    pub increment: &'static str,
}

impl CpuPass for Kick {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| kick(cx, self, kept, sep))
    }
}

fn kick<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, pass: &Kick, kept: K, sep: S) {
    let dt = cx.dt;
    let (vh, kh) = (cx.attrs.handle::<Vec3>("v"), cx.attrs.handle::<Real>(pass.kappa));
    let (mut vel, mut kappa) = (cx.attrs.take(vh), cx.attrs.take(kh));
    let attrs = &*cx.attrs;
    let dp = attrs.get(attrs.handle::<Real>(pass.increment));
    let sums = Sums::new(cx.model, attrs, kept, sep);
    let outputs = vel.par_chunks_mut(CHUNK).zip(kappa.par_chunks_mut(CHUNK));
    outputs.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((out, kappa), nb))| {
        for (n, v) in out.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            kappa[n] += dp[i];
            *v -= sums.gradient(i, n, nb, dp) * dt;
        }
    });
    cx.attrs.put(vh, vel);
    cx.attrs.put(kh, kappa);
}

/// A solve's error from the current velocities: its increment `dP = e alpha / dt^2`
/// (density) or `e alpha / dt` (divergence) for the compression `e >= 0`, and its
/// residual.
#[derive(Debug)]
pub struct Error {
    /// The constant-density solve's (else the divergence-free solve's).
    pub density: bool,
}

impl CpuPass for Error {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| match self.density {
            true => error::<true, _, _>(cx, kept, sep),
            false => error::<false, _, _>(cx, kept, sep),
        })
    }
}

fn error<const DENSITY: bool, K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let dt = cx.dt;
    let (names, scale) =
        if DENSITY { (["dkappa", "density_error"], dt * dt) } else { (["dkappa_v", "divergence_error"], dt) };
    let handles = names.map(|n| cx.attrs.handle::<Real>(n));
    let [mut inc, mut err] = handles.map(|h| cx.attrs.take(h));
    let attrs = &*cx.attrs;
    let vel = attrs.get(attrs.handle::<Vec3>("v"));
    let (rho, alpha) = (attrs.get(attrs.handle::<Real>("rho")), attrs.get(attrs.handle::<Real>("alpha")));
    let sums = Sums::new(cx.model, attrs, kept, sep);
    let outputs = inc.par_chunks_mut(CHUNK).zip(err.par_chunks_mut(CHUNK));
    outputs.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((inc, err), nb))| {
        for n in 0..inc.len() {
            let i = c * CHUNK + n;
            let rest_density = sums.material(i).rest_density;
            let rate = sums.divergence(i, n, nb, vel);
            // Only compression is corrected: the error is clamped at zero, so each
            // iteration only adds to the stiffness (SPlisHSPlasH's update).
            let compression = if DENSITY {
                rho[i] + dt * rate - rest_density
            } else if neighbours(nb, n) >= FULL_NEIGHBOURHOOD {
                rate
            } else {
                0.0
            };
            let e = compression.max(0.0);
            inc[n] = e * alpha[i] / scale;
            let residual = if DENSITY { e } else { dt * e };
            err[n] = residual / rest_density;
        }
    });
    for (h, col) in handles.into_iter().zip([inc, err]) {
        cx.attrs.put(h, col);
    }
}
