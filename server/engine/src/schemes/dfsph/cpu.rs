//! DFSPH's passes on the CPU, over the step's neighbour lists (the formulas are in
//! the scheme's documentation; the GPU's kernels add the same terms in the same
//! order).
//!
//! The factor pass keeps every pair's kernel gradient beside the neighbour rows
//! ([`crate::cpu::neighbors::ChunkNeighbors::keep_gradients`]) and the solves' passes
//! read them back: the positions do not move between the factor and the drift, and
//! a step iterates each solve several times (about 9 iterations of two passes per
//! step on the dam break), so the gradients are evaluated once instead of once per
//! pass.

use super::{FULL_NEIGHBOURHOOD, WARM_START};
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::kernel::Kernel;
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use rayon::prelude::*;

/// `grad W` for the separation `x` (zero for coinciding particles, as in the forces).
#[inline(always)]
fn gradient(k: &Kernel, x: Vec3) -> Vec3 {
    let r2 = x.length_squared();
    if r2 == 0.0 {
        return Vec3::ZERO;
    }
    let r = r2.sqrt();
    x * (k.dw_dr(r) / r)
}

/// `alpha = 1 / (s . t + m_i^2 sum_j (m_i / m_j) |grad W_ij|^2)`, 0 for a particle
/// without neighbours.
#[derive(Debug)]
pub struct Factor;

impl CpuPass for Factor {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| factor(cx, s))
    }
}

fn factor<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let (k, walls, materials) = (&model.kernel, &model.wall_particles, &model.materials);
    let h = cx.attrs.handle::<Real>("alpha");
    let mut alpha = cx.attrs.take(h);
    let attrs = &*cx.attrs;
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    alpha.par_chunks_mut(CHUNK).zip(cx.nb.chunks.par_iter_mut()).enumerate().for_each(|(c, (out, nb))| {
        nb.keep_gradients(
            |n, j| gradient(k, sep.between(pos[c * CHUNK + n], pos[j])),
            |n, b| gradient(k, sep.between(pos[c * CHUNK + n], walls.positions[b])),
        );
        for (n, a) in out.iter_mut().enumerate() {
            let mi = material(c * CHUNK + n);
            let m_i = materials.get(mi).mass;
            let (mut fluid, mut sq) = (Vec3::ZERO, 0.0);
            for (&j, &g) in nb.fluid(n).iter().zip(nb.fluid_gradients(n)) {
                fluid += g * m_i;
                sq += g.length_squared() * (m_i / materials.get(material(j as usize)).mass);
            }
            let psi = &walls.psi[mi];
            let mut wall = Vec3::ZERO;
            for (&b, &g) in nb.walls(n).iter().zip(nb.wall_gradients(n)) {
                wall += g * psi[b as usize];
            }
            let d = (fluid + wall).length_squared() + m_i * m_i * sq;
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
        let (kh, dh) = (cx.attrs.handle::<Real>(self.kappa), cx.attrs.handle::<Real>(self.increment));
        let (mut kappa, mut inc) = (cx.attrs.take(kh), cx.attrs.take(dh));
        kappa.par_iter_mut().zip(inc.par_iter_mut()).with_min_len(4096).for_each(|(k, d)| {
            *d = WARM_START * *k;
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
        kick(cx, self)
    }
}

fn kick(cx: &mut CpuCx<'_>, pass: &Kick) {
    let model = cx.model;
    let (walls, materials) = (&model.wall_particles, &model.materials);
    let dt = cx.dt;
    let (vh, kh) = (cx.attrs.handle::<Vec3>("v"), cx.attrs.handle::<Real>(pass.kappa));
    let (mut vel, mut kappa) = (cx.attrs.take(vh), cx.attrs.take(kh));
    let attrs = &*cx.attrs;
    let dp = attrs.get(attrs.handle::<Real>(pass.increment));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    let outputs = vel.par_chunks_mut(CHUNK).zip(kappa.par_chunks_mut(CHUNK));
    outputs.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((out, kappa), nb))| {
        for (n, v) in out.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            kappa[n] += dp[i];
            let mi = material(i);
            let m_i = materials.get(mi).mass;
            let own = m_i * dp[i];
            let mut a = Vec3::ZERO;
            for (&j, &g) in nb.fluid(n).iter().zip(nb.fluid_gradients(n)) {
                let j = j as usize;
                let m_j = materials.get(material(j)).mass;
                a += g * (own + m_j * m_j / m_i * dp[j]);
            }
            let psi = &walls.psi[mi];
            let mut wall = Vec3::ZERO;
            for (&b, &g) in nb.walls(n).iter().zip(nb.wall_gradients(n)) {
                wall += g * psi[b as usize];
            }
            *v -= (a + wall * dp[i]) * dt;
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
        match self.density {
            true => error::<true>(cx),
            false => error::<false>(cx),
        }
    }
}

fn error<const DENSITY: bool>(cx: &mut CpuCx<'_>) {
    let model = cx.model;
    let (walls, materials) = (&model.wall_particles, &model.materials);
    let dt = cx.dt;
    let (names, scale) =
        if DENSITY { (["dkappa", "density_error"], dt * dt) } else { (["dkappa_v", "divergence_error"], dt) };
    let handles = names.map(|n| cx.attrs.handle::<Real>(n));
    let [mut inc, mut err] = handles.map(|h| cx.attrs.take(h));
    let attrs = &*cx.attrs;
    let vel = attrs.get(attrs.handle::<Vec3>("v"));
    let (rho, alpha) = (attrs.get(attrs.handle::<Real>("rho")), attrs.get(attrs.handle::<Real>("alpha")));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    let outputs = inc.par_chunks_mut(CHUNK).zip(err.par_chunks_mut(CHUNK));
    outputs.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((inc, err), nb))| {
        for n in 0..inc.len() {
            let i = c * CHUNK + n;
            let (vi, mi) = (vel[i], material(i));
            let m = materials.get(mi);
            let mut fluid = 0.0;
            for (&j, &g) in nb.fluid(n).iter().zip(nb.fluid_gradients(n)) {
                fluid += (vi - vel[j as usize]).dot(g);
            }
            let psi = &walls.psi[mi];
            let mut wall = 0.0;
            for (&b, &g) in nb.walls(n).iter().zip(nb.wall_gradients(n)) {
                wall += psi[b as usize] * vi.dot(g);
            }
            let rate = m.mass * fluid + wall;
            // Only compression is corrected: the error is clamped at zero, so each
            // iteration only adds to the stiffness (SPlisHSPlasH's update).
            let compression = if DENSITY {
                rho[i] + dt * rate - m.rest_density
            } else if (nb.fluid(n).len() - 1 + nb.walls(n).len()) as u32 >= FULL_NEIGHBOURHOOD {
                rate
            } else {
                0.0
            };
            let e = compression.max(0.0);
            inc[n] = e * alpha[i] / scale;
            let residual = if DENSITY { e } else { dt * e };
            err[n] = residual / m.rest_density;
        }
    });
    for (h, col) in handles.into_iter().zip([inc, err]) {
        cx.attrs.put(h, col);
    }
}
