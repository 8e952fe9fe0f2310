//! The conjugate-gradient solves' passes on the CPU ([`super::cg`] has the system and
//! the order); the pair sums are the Jacobi's (`cpu::Sums`), over the
//! gradients the factor pass kept.

use super::cg::{
    HELD, IS_CLOSED, IS_OPEN, PAP, RAW_EXCESS, RSUM, RZ, RZ_NEW, SHIFT_ANTI_CLUSTERING, SHIFT_LIMIT, SHIFT_MOST,
    SURFACE_DENSITY, SURFACE_GRADIENT, UNDECIDED, ratio,
};
use super::cpu::{Kept, Sums, neighbours, with_kept};
use super::{FULL_NEIGHBOURHOOD, WARM_START};
use crate::cpu::neighbors::{CHUNK, gather};
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use rayon::prelude::*;

/// The solves' scalars.
fn scalars(cx: &CpuCx<'_>) -> Vec<Real> {
    cx.attrs.get(cx.attrs.handle::<Real>("dfsph_scalars")).to_vec()
}

/// `dfsph.cg_held`: 1 for a particle held at `P = 0` (a free surface: fewer than
/// [`FULL_NEIGHBOURHOOD`] neighbours, a summed density below [`SURFACE_DENSITY`] of
/// rest, or below rest with a neighbourhood the surface cuts, [`SURFACE_GRADIENT`]),
/// else 0; 0 for every particle of a closed scene.
#[derive(Debug)]
pub struct Held;

impl CpuPass for Held {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| held(cx, kept, sep))
    }
}

fn held<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let cut = SURFACE_GRADIENT / cx.model.kernel.support();
    let closed = cx.attrs.get(cx.attrs.handle::<Real>("dfsph_closed"))[0] == IS_CLOSED;
    let h = cx.attrs.handle::<Real>("dfsph_held");
    let mut held = cx.attrs.take(h);
    let sums = Sums::new(cx.model, &*cx.attrs, kept, sep);
    let rho = cx.attrs.get(cx.attrs.handle::<Real>("rho"));
    held.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (out, nb))| {
        for (n, held) in out.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let rest = sums.material(i).rest_density;
            let surface = rho[i] < rest && sums.volume_gradient(i, n, nb).length_squared() >= cut * cut;
            let free = neighbours(nb, n) >= FULL_NEIGHBOURHOOD && rho[i] >= SURFACE_DENSITY * rest && !surface;
            *held = if closed || free { 0.0 } else { 1.0 };
        }
    });
    cx.attrs.put(h, held);
}

/// `dfsph.cg_closed`: before the first step's decision, the scene is closed if no
/// particle is held ([`IS_CLOSED`]), else open ([`IS_OPEN`]); later, nothing.
#[derive(Debug)]
pub struct Closed;

impl CpuPass for Closed {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let held = scalars(cx)[HELD as usize];
        let h = cx.attrs.handle::<Real>("dfsph_closed");
        let mut closed = cx.attrs.take(h);
        if closed[0] == UNDECIDED {
            closed[0] = if held == 0.0 { IS_CLOSED } else { IS_OPEN };
        }
        cx.attrs.put(h, closed);
    }
}

/// `dfsph.cg_shift`: each particle's shift ([`super::cg`]) from the current
/// positions, its neighbours found on the step's grid (as a GPU's walk finds them).
#[derive(Debug)]
pub struct Shift;

impl CpuPass for Shift {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |sep| shift(cx, sep))
    }
}

fn shift<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let (kernel, walls, dx) = (&model.kernel, &model.wall_particles, model.spacing);
    let h = 0.5 * kernel.support();
    // cx.dt: the step's largest displacement v_max dt (m).
    let a = model.consts::<super::DfsphConsts>().settings.shift;
    let step = (a * h * cx.dt).min(SHIFT_MOST * h * h);
    let (limit, w_dx, h2) = (SHIFT_LIMIT * dx, kernel.w_r2(dx * dx), kernel.support() * kernel.support());
    // The pair's weight `V (1 + R (W / W(dx))^4) |grad W| / r` along x_ij.
    let weight = |x: Vec3, volume: Real| {
        let r2 = x.length_squared();
        let f = kernel.w_r2(r2) / w_dx;
        kernel.grad(x, r2.sqrt()) * (volume * (1.0 + SHIFT_ANTI_CLUSTERING * (f * f) * (f * f)))
    };
    let handle = cx.attrs.handle::<Vec3>("dfsph_shift");
    let mut out = cx.attrs.take(handle);
    let attrs = &*cx.attrs;
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let grid = &*cx.grid;
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let (mut fluid, mut wall) = (Vec::new(), Vec::new());
        for (n, o) in out.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let (xi, mi) = (pos[i], mat.map_or(0, |m| m[i] as usize));
            fluid.clear();
            gather(sep, grid, pos, xi, h2, &mut fluid);
            let mut g = Vec3::ZERO;
            for &j in &fluid {
                let m = model.materials.get(mat.map_or(0, |m| m[j as usize] as usize));
                let x_ij = sep.between(xi, pos[j as usize]);
                if x_ij != Vec3::ZERO {
                    g += weight(x_ij, m.mass / m.rest_density);
                }
            }
            wall.clear();
            gather(sep, &walls.grid, &walls.positions, xi, h2, &mut wall);
            let (psi, rho0) = (&walls.psi[mi], model.materials.get(mi).rest_density);
            for &b in &wall {
                g += weight(sep.between(xi, walls.positions[b as usize]), psi[b as usize] / rho0);
            }
            let d = g * -step;
            *o = if d.length() > limit { d * (limit / d.length()) } else { d };
        }
    });
    cx.attrs.put(handle, out);
}

/// `dfsph.cg_shift_apply`: `x += dfsph_shift`, back through a periodic face.
#[derive(Debug)]
pub struct ShiftApply;

impl CpuPass for ShiftApply {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let h = cx.attrs.handle::<Vec3>("x");
        let mut x = cx.attrs.take(h);
        let shift = cx.attrs.get(cx.attrs.handle::<Vec3>("dfsph_shift"));
        let periodic = &cx.model.periodic;
        x.par_iter_mut().zip(shift).with_min_len(4096).for_each(|(x, d)| *x = periodic.wrap(*x + *d));
        cx.attrs.put(h, x);
    }
}

/// `dfsph.cg_wall_pressure`: the walls' hydrostatic part of their pressure as a
/// kick, `v_i -= dt sum_b psi_b P'_b grad W_ib` with
/// `P'_b = g . (x_b - x_i) / rho0_i`, at a free surface no less than
/// `-(kappa_i + kappa_v_i)` (a wall particle's pressure is not negative; [`super::cg`]).
#[derive(Debug)]
pub struct WallPressure;

impl CpuPass for WallPressure {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| wall_pressure(cx, kept, sep))
    }
}

fn wall_pressure<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let surface = scalars(cx)[HELD as usize] > 0.0;
    let (dt, model) = (cx.dt, cx.model);
    let (walls, g) = (&model.wall_particles, model.gravity);
    let h = cx.attrs.handle::<Vec3>("v");
    let mut vel = cx.attrs.take(h);
    let attrs = &*cx.attrs;
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let (kappa, kappa_v) = (attrs.get(attrs.handle::<Real>("kappa")), attrs.get(attrs.handle::<Real>("kappa_v")));
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    vel.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (out, nb))| {
        for (n, v) in out.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let m = mat.map_or(0, |m| m[i] as usize);
            let (psi, rho0) = (&walls.psi[m], model.materials.get(m).rest_density);
            let least = if surface { -(kappa[i] + kappa_v[i]) } else { Real::NEG_INFINITY };
            let mut a = Vec3::ZERO;
            for (&b, &k) in nb.walls(n).iter().zip(nb.wall_kept::<K::Value>(n)) {
                let x_ib = sep.between(pos[i], walls.positions[b as usize]);
                a += kept.scaled(k, || x_ib, psi[b as usize] * (-g.dot(x_ib) / rho0).max(least));
            }
            *v -= a * dt;
        }
    });
    cx.attrs.put(h, vel);
}

/// `dfsph.cg_{density,divergence}_warm`: the Jacobi's warm start
/// ([`super::cpu::Warm`]) from all of the last stiffness where a free surface exists,
/// else from [`WARM_START`] of it ([`super::cg`]); none for a held particle, whose
/// stiffness is zero.
#[derive(Debug)]
pub struct Warm(pub super::cpu::Warm);

impl CpuPass for Warm {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let w = if scalars(cx)[HELD as usize] > 0.0 { 1.0 } else { WARM_START };
        self.0.start(cx, w, Some("dfsph_held"));
    }
}

/// `dfsph.cg_{density,divergence}_start`: `r = b` from the current velocities, 0
/// for a held particle; in a closed domain the density's deviation filtered
/// ([`RAW_EXCESS`]).
#[derive(Debug)]
pub struct Start {
    /// The constant-density solve's (else the divergence-free solve's).
    pub density: bool,
}

impl CpuPass for Start {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| start(cx, self.density, kept, sep))
    }
}

fn start<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, density: bool, kept: K, sep: S) {
    let (dt, kernel) = (cx.dt, &cx.model.kernel);
    let closed = scalars(cx)[HELD as usize] == 0.0;
    let rh = cx.attrs.handle::<Real>("dfsph_r");
    let mut r = cx.attrs.take(rh);
    let attrs = &*cx.attrs;
    let (vel, rho) = (attrs.get(attrs.handle::<Vec3>("v")), attrs.get(attrs.handle::<Real>("rho")));
    let pos = attrs.get(attrs.handle::<Vec3>("x"));
    let held = attrs.get(attrs.handle::<Real>("dfsph_held"));
    let sums = Sums::new(cx.model, attrs, kept, sep);
    r.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (r, nb))| {
        for (n, r) in r.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            *r = if held[i] != 0.0 {
                0.0
            } else if density && closed {
                // Shepard's mean of the deviation over the fluid neighbours (the
                // particle itself included), with RAW_EXCESS of its own difference.
                let rest = sums.material(i).rest_density;
                let (mut sum, mut weight) = (0.0, 0.0);
                for &j in nb.fluid(n) {
                    let w = kernel.w_r2(sums.separation(pos[i], pos[j as usize]).length_squared());
                    sum += w * (rho[j as usize] - rest);
                    weight += w;
                }
                let mean = sum / weight;
                let excess = mean + RAW_EXCESS * (rho[i] - rest - mean);
                (excess + dt * sums.divergence(i, n, nb, vel)) / (dt * dt)
            } else if density {
                (rho[i] + dt * sums.divergence(i, n, nb, vel) - sums.material(i).rest_density) / (dt * dt)
            } else {
                sums.divergence(i, n, nb, vel) / dt
            };
        }
    });
    cx.attrs.put(rh, r);
}

/// `dfsph.cg_{density,divergence}_adjust`: with no particle held, the starting
/// residual's mean removed; with some, the density solve's start raised to
/// `max(rho, rho0)`; then the first direction `p = alpha r`.
#[derive(Debug)]
pub struct Adjust {
    /// The constant-density solve's (else the divergence-free solve's).
    pub density: bool,
}

impl CpuPass for Adjust {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let s = scalars(cx);
        let (dt, model) = (cx.dt, cx.model);
        let (rh, ph) = (cx.attrs.handle::<Real>("dfsph_r"), cx.attrs.handle::<Real>("dfsph_p"));
        let (mut r, mut p) = (cx.attrs.take(rh), cx.attrs.take(ph));
        let attrs = &*cx.attrs;
        let (rho, alpha) = (attrs.get(attrs.handle::<Real>("rho")), attrs.get(attrs.handle::<Real>("alpha")));
        let held = attrs.get(attrs.handle::<Real>("dfsph_held"));
        let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
        let closed = s[HELD as usize] == 0.0;
        let mean = s[RSUM as usize] / r.len().max(1) as Real;
        r.par_iter_mut().zip(p.par_iter_mut()).enumerate().for_each(|(i, (r, p))| {
            if closed {
                *r -= mean;
            } else if self.density && held[i] == 0.0 {
                let rest = model.materials.get(mat.map_or(0, |m| m[i] as usize)).rest_density;
                *r += (rest - rho[i]).max(0.0) / (dt * dt);
            }
            *p = alpha[i] * *r;
        });
        cx.attrs.put(rh, r);
        cx.attrs.put(ph, p);
    }
}

/// `dfsph.cg_{density,divergence}_residual`: each particle's `r alpha r` and its
/// residual `|r| dt^2 / rho0`.
#[derive(Debug)]
pub struct Residual {
    /// The solve's residual attribute.
    pub residual: &'static str,
}

impl CpuPass for Residual {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (dt, model) = (cx.dt, cx.model);
        let (dh, eh) = (cx.attrs.handle::<Real>("dfsph_dot"), cx.attrs.handle::<Real>(self.residual));
        let (mut dot, mut err) = (cx.attrs.take(dh), cx.attrs.take(eh));
        let attrs = &*cx.attrs;
        let (r, alpha) = (attrs.get(attrs.handle::<Real>("dfsph_r")), attrs.get(attrs.handle::<Real>("alpha")));
        let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
        dot.par_iter_mut().zip(err.par_iter_mut()).enumerate().for_each(|(i, (dot, err))| {
            let rest = model.materials.get(mat.map_or(0, |m| m[i] as usize)).rest_density;
            *dot = r[i] * alpha[i] * r[i];
            *err = r[i].abs() * dt * dt / rest;
        });
        cx.attrs.put(dh, dot);
        cx.attrs.put(eh, err);
    }
}

/// `dfsph.cg_gradient`: `G p`.
#[derive(Debug)]
pub struct Gradient;

impl CpuPass for Gradient {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| gradient(cx, kept, sep))
    }
}

fn gradient<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let h = cx.attrs.handle::<Vec3>("dfsph_gp");
    let mut gp = cx.attrs.take(h);
    let attrs = &*cx.attrs;
    let p = attrs.get(attrs.handle::<Real>("dfsph_p"));
    let sums = Sums::new(cx.model, attrs, kept, sep);
    gp.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (out, nb))| {
        for (n, g) in out.iter_mut().enumerate() {
            *g = sums.gradient(c * CHUNK + n, n, nb, p);
        }
    });
    cx.attrs.put(h, gp);
}

/// `dfsph.cg_product`: `A p = D G p` (0 for a held particle) and `p . Ap` per
/// particle.
#[derive(Debug)]
pub struct Product;

impl CpuPass for Product {
    fn run(&self, cx: &mut CpuCx<'_>) {
        with_kept!(cx.model, |kept, sep| product(cx, kept, sep))
    }
}

fn product<K: Kept, S: Separation>(cx: &mut CpuCx<'_>, kept: K, sep: S) {
    let (ah, dh) = (cx.attrs.handle::<Real>("dfsph_ap"), cx.attrs.handle::<Real>("dfsph_dot"));
    let (mut ap, mut dot) = (cx.attrs.take(ah), cx.attrs.take(dh));
    let attrs = &*cx.attrs;
    let (gp, p) = (attrs.get(attrs.handle::<Vec3>("dfsph_gp")), attrs.get(attrs.handle::<Real>("dfsph_p")));
    let held = attrs.get(attrs.handle::<Real>("dfsph_held"));
    let sums = Sums::new(cx.model, attrs, kept, sep);
    let outputs = ap.par_chunks_mut(CHUNK).zip(dot.par_chunks_mut(CHUNK));
    outputs.zip(&cx.nb.chunks).enumerate().for_each(|(c, ((ap, dot), nb))| {
        for n in 0..ap.len() {
            let i = c * CHUNK + n;
            ap[n] = if held[i] == 0.0 { sums.divergence(i, n, nb, gp) } else { 0.0 };
            dot[n] = p[i] * ap[n];
        }
    });
    cx.attrs.put(ah, ap);
    cx.attrs.put(dh, dot);
}

/// `dfsph.cg_{density,divergence}_update`: `a = RZ / PAP`, `P += a p`,
/// `v -= dt a G p`, `r -= a A p`.
#[derive(Debug)]
pub struct Update {
    /// The solve's stiffness.
    pub kappa: &'static str,
}

impl CpuPass for Update {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let s = scalars(cx);
        let (a, dt) = (ratio(s[RZ as usize], s[PAP as usize]), cx.dt);
        let (vh, kh, rh) =
            (cx.attrs.handle::<Vec3>("v"), cx.attrs.handle::<Real>(self.kappa), cx.attrs.handle::<Real>("dfsph_r"));
        let (mut v, mut kappa, mut r) = (cx.attrs.take(vh), cx.attrs.take(kh), cx.attrs.take(rh));
        let attrs = &*cx.attrs;
        let (p, gp, ap) = (
            attrs.get(attrs.handle::<Real>("dfsph_p")),
            attrs.get(attrs.handle::<Vec3>("dfsph_gp")),
            attrs.get(attrs.handle::<Real>("dfsph_ap")),
        );
        let outputs = v.par_iter_mut().zip(kappa.par_iter_mut()).zip(r.par_iter_mut());
        outputs.enumerate().for_each(|(i, ((v, kappa), r))| {
            *kappa += a * p[i];
            *v -= gp[i] * (dt * a);
            *r -= a * ap[i];
        });
        cx.attrs.put(vh, v);
        cx.attrs.put(kh, kappa);
        cx.attrs.put(rh, r);
    }
}

/// `dfsph.cg_direction`: `p = alpha r + (RZ_NEW / RZ) p`.
#[derive(Debug)]
pub struct Direction;

impl CpuPass for Direction {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let s = scalars(cx);
        let beta = ratio(s[RZ_NEW as usize], s[RZ as usize]);
        let h = cx.attrs.handle::<Real>("dfsph_p");
        let mut p = cx.attrs.take(h);
        let attrs = &*cx.attrs;
        let (r, alpha) = (attrs.get(attrs.handle::<Real>("dfsph_r")), attrs.get(attrs.handle::<Real>("alpha")));
        p.par_iter_mut().enumerate().for_each(|(i, p)| *p = alpha[i] * r[i] + beta * *p);
        cx.attrs.put(h, p);
    }
}

/// `dfsph.cg_{density,divergence}_clamp`: where a free surface exists (some particle
/// held), the increment `max(P, 0) - P` that the solve's kick then applies; else 0.
#[derive(Debug)]
pub struct Clamp {
    /// The solve's stiffness.
    pub kappa: &'static str,
    /// The solve's increment.
    pub increment: &'static str,
}

impl CpuPass for Clamp {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let surface = scalars(cx)[HELD as usize] > 0.0;
        let h = cx.attrs.handle::<Real>(self.increment);
        let mut inc = cx.attrs.take(h);
        let kappa = cx.attrs.get(cx.attrs.handle::<Real>(self.kappa));
        inc.par_iter_mut().zip(kappa).for_each(|(d, &k)| *d = if surface { (-k).max(0.0) } else { 0.0 });
        cx.attrs.put(h, inc);
    }
}
