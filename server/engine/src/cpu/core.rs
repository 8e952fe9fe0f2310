//! The core's passes on the CPU: the sort by cell, summation density (which also
//! finds the step's neighbour lists), the guard's and time step's reduction, and the
//! integrators' two halves.
//!
//! Density by summation, walls included (Akinci et al. 2012, eq. 6; several
//! materials after Solenthaler & Pajarola 2008, eq. 4):
//! `rho_i = m_i sum_j W_ij + sum_b psi_b W_ib`, with the wall pseudo-mass `psi_b`
//! of particle i's material.

use super::neighbors::CHUNK;
use super::{CpuCx, CpuPass};
use crate::guard::Measures;
use crate::math::{Real, Vec3};
use crate::model::Model;
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// Re-sorts the particle space by grid cell.
pub static SORT: PassSpec = PassSpec {
    name: "core.sort",
    module: "core",
    stage: Stage::Sort,
    reads: &["x", "id"],
    writes: &["slot_of"],
    accumulates: &[],
    tolerance: 0.0,
};

/// Summation density.
pub static DENSITY: PassSpec = PassSpec {
    name: "core.density",
    module: "core",
    stage: Stage::Density,
    reads: &["x"],
    writes: &["rho"],
    accumulates: &[],
    tolerance: 1e-5,
};

/// The neighbour search alone, in place of [`DENSITY`] in scenes whose scheme
/// integrates the density (δ-SPH): the CPU fills the step's neighbour lists; the
/// GPU, which searches the sorted grid in every pass, has nothing to do.
pub static NEIGHBOURS: PassSpec = PassSpec {
    name: "core.neighbours",
    module: "core",
    stage: Stage::Density,
    reads: &["x"],
    writes: &[],
    accumulates: &[],
    tolerance: 0.0,
};

/// The core's CPU passes, by name.
pub static PASSES: &[(&str, &dyn CpuPass)] =
    &[("core.sort", &Sort), ("core.density", &Density::<true>), ("core.neighbours", &Density::<false>)];

/// Counting sort by cell (stable: sorting sorted particles changes nothing); every
/// state attribute of the particle space follows, and `slot_of` is rebuilt (where
/// the scene has it: not where particles are born and die).
#[derive(Debug)]
struct Sort;

impl CpuPass for Sort {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let x = cx.attrs.handle::<Vec3>("x");
        cx.grid.sort(cx.attrs.get(x), &mut cx.sort.cells, &mut cx.sort.order);
        cx.attrs.permute(crate::attrs::PARTICLES, &cx.sort.order);
        let Some(slot) = cx.attrs.find::<u32>("slot_of") else { return };
        let ids = cx.attrs.handle::<u32>("id");
        let mut slot_of = cx.attrs.take(slot);
        for (k, &id) in cx.attrs.get(ids).iter().enumerate() {
            slot_of[id as usize] = k as u32;
        }
        cx.attrs.put(slot, slot_of);
    }
}

/// Finds every particle's neighbours into the step's lists and, when `SUM`, fills
/// `rho` (kg/m^3).
#[derive(Debug)]
struct Density<const SUM: bool>;

impl<const SUM: bool> CpuPass for Density<SUM> {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| density::<SUM, _>(cx, s))
    }
}

fn density<const SUM: bool, S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let h2 = k.support() * k.support();
    let walls = &model.wall_particles;
    let x = cx.attrs.handle::<Vec3>("x");
    // Summing, the density's values are reused in place.
    let summed = SUM.then(|| {
        let h = cx.attrs.handle::<Real>("rho");
        (h, cx.attrs.take(h))
    });
    let pos = cx.attrs.get(x);
    let grid = &*cx.grid;
    let count = pos.len();
    cx.nb.chunks.resize_with(count.div_ceil(CHUNK), Default::default);
    let lists = |c: usize, nb: &mut crate::cpu::neighbors::ChunkNeighbors| {
        nb.clear();
        for i in c * CHUNK..((c + 1) * CHUNK).min(count) {
            nb.push(sep, grid, pos, &walls.grid, &walls.positions, pos[i], h2);
        }
    };
    let Some((rho_h, mut rho)) = summed else {
        // The neighbour lists alone (a scheme that integrates the density).
        cx.nb.chunks.par_iter_mut().enumerate().for_each(|(c, nb)| lists(c, nb));
        return;
    };
    let materials = cx.attrs.find::<u32>("material").map(|m| cx.attrs.get(m));
    rho.par_chunks_mut(CHUNK).zip(cx.nb.chunks.par_iter_mut()).enumerate().for_each(|(c, (rho_c, nb))| {
        lists(c, nb);
        for (n, rho_i) in rho_c.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let xi = pos[i];
            let a = materials.map_or(0, |m| m[i] as usize);
            let (m, psi) = (model.materials.get(a).mass, &walls.psi[a]);
            let sum: Real =
                nb.fluid(n).iter().map(|&j| k.w_r2(sep.between(xi, pos[j as usize]).length_squared())).sum();
            let wall: Real = nb
                .walls(n)
                .iter()
                .map(|&b| psi[b as usize] * k.w_r2(sep.between(xi, walls.positions[b as usize]).length_squared()))
                .sum();
            *rho_i = m * sum + wall;
        }
    });
    cx.attrs.put(rho_h, rho);
}

/// Reduces the state to what the guard and the time step control need: largest
/// speed and acceleration, largest compression relative to each particle's own
/// material, the first non-finite position, velocity, acceleration or density, the
/// first particle outside the domain. Modules guard their own state with bounds
/// ([`crate::guard::Bound`]).
pub fn measure(model: &Model, attrs: &crate::attrs::Attrs) -> Measures {
    let (pos, vel) = (attrs.get(attrs.handle::<Vec3>("x")), attrs.get(attrs.handle::<Vec3>("v")));
    let (acc, rho) = (attrs.get(attrs.handle::<Vec3>("a")), attrs.get(attrs.handle::<Real>("rho")));
    let materials = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let domain = model.domain;
    let rho0 = |i: usize| model.materials.get(materials.map_or(0, |m| m[i] as usize)).rest_density;
    (0..pos.len())
        .into_par_iter()
        .with_min_len(4 * CHUNK)
        .fold(Measures::default, |mut m, i| {
            let (x, v, a) = (pos[i], vel[i], acc[i]);
            let slot = i as u32;
            if !(x.is_finite() && v.is_finite() && a.is_finite() && rho[i].is_finite()) {
                m.non_finite.get_or_insert(slot);
                return m;
            }
            let s2 = v.length_squared();
            if s2 > m.max_speed2.0 {
                m.max_speed2 = (s2, slot);
            }
            m.max_accel2 = m.max_accel2.max(a.length_squared());
            let r0 = rho0(i);
            let c = (rho[i] - r0) / r0;
            if c > m.max_compression.0 {
                m.max_compression = (c, slot);
            }
            m.sum_compression += c.max(0.0) as f64;
            if !domain.contains(x) {
                m.outside.get_or_insert(slot);
            }
            m
        })
        .reduce(Measures::default, Measures::merge)
}

/// `v = (v + dt a) keep`.
pub fn kick(attrs: &mut crate::attrs::Attrs, dt: Real, keep: Real) {
    let (v, a) = (attrs.handle::<Vec3>("v"), attrs.handle::<Vec3>("a"));
    let mut vel = attrs.take(v);
    vel.par_iter_mut().zip(attrs.get(a).par_iter()).with_min_len(4096).for_each(|(v, &a)| {
        *v = (*v + a * dt) * keep;
    });
    attrs.put(v, vel);
}

/// `x += dt v` (with `v + dt/2 a_transport` in scenes that have that attribute),
/// then the walls' non-penetration constraints (and a terrain's friction, which takes
/// gravity times dt as part of the normal load, on the ground as `ground_height`
/// has it now); positions that left through a periodic face come back through the
/// opposite one.
pub fn drift(model: &Model, attrs: &mut crate::attrs::Attrs, dt: Real) {
    let (x, v) = (attrs.handle::<Vec3>("x"), attrs.handle::<Vec3>("v"));
    let (mut pos, mut vel) = (attrs.take(x), attrs.take(v));
    let transport = attrs.find::<Vec3>("a_transport").map(|t| attrs.get(t));
    let ground: &[Real] = attrs.find::<Real>(crate::terrain::GROUND.name).map_or(&[], |g| attrs.get(g));
    let walls = &model.wall_constraints;
    let periodic = &model.periodic;
    let (g_dt, half) = (model.gravity * dt, 0.5 * dt);
    pos.par_iter_mut().zip(vel.par_iter_mut()).enumerate().with_min_len(4096).for_each(|(i, (x, v))| {
        match transport {
            Some(t) => *x += (*v + t[i] * half) * dt,
            None => *x += *v * dt,
        }
        for w in walls {
            w.apply(x, v, g_dt, ground);
        }
        if periodic.any() {
            *x = periodic.wrap(*x);
        }
    });
    attrs.put(x, pos);
    attrs.put(v, vel);
}
