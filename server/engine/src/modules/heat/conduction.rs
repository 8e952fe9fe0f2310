//! Conduction by the SPH Laplacian of Cleary & Monaghan (1999, J. Comput. Phys.
//! 148, eq. 9), with the conductivities of a pair combined as twice their harmonic
//! mean so the flux across an interface between materials is continuous:
//!
//! `dT_i/dt = 1/c_i sum_j m_j / (rho_i rho_j) K_ij (T_i - T_j) F_ij + q_i / (rho_i c_i)`,
//! `K_ij = 4 k_i k_j / (k_i + k_j)`, `F_ij = x_ij . grad_i W_ij / (r_ij^2 + 0.01 h^2)`.
//!
//! Multiplied by `m_i c_i` the pair term is antisymmetric in (i, j), so the total
//! heat `sum_i m_i c_i T_i` changes only through walls and sources. A wall particle
//! b held at `T_b` joins the sum with its pseudo-mass `psi_b`, `rho_b = rho0_i`
//! and the fluid's own conductivity (`K = 2 k_i`), as the mirror image of the fluid
//! particle (temperature `2 T_b - T_i`: the term `2 (T_i - T_b)` puts `T_b` on the
//! wall's surface, as Morris et al. 1997 do for no-slip velocities); other walls are
//! insulated.
//! `q_i` is the power density of the sources around particle i (W/m^3), and of the
//! wall fluxes whose layer it is in: `q_w d^2 rho_i / m_i`, so that the particle
//! takes `q_w d^2` watts, the flux through the wall area it covers on the lattice.
//!
//! On a lattice with a support of a few spacings the sum misses the Laplacian by a
//! fixed fraction (about 1 % for the cubic spline at two spacings), which no
//! refinement at a fixed support ratio removes; [`Kernel::pair_lattice_scale`](crate::kernel::Kernel::pair_lattice_scale) divides it out,
//! as the particle mass divides out the lattice's kernel sum.
//!
//! Where a fluid melts and heat enters through walls or sources, the pass also
//! writes the part of `dT/dt` from walls and sources alone (`heat_input`), which
//! [`super::phase::Input`] sums into the heat each particle took from outside:
//! the energy balance of the Stefan problem (docs/ice.md).
//!
//! The sums run in the same order as the GPU's `conduction.wgsl`.

use super::HeatConsts;
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// dT/dt from conduction and sources.
pub static CONDUCTION: PassSpec = PassSpec {
    name: "heat.conduction",
    module: "heat",
    stage: Stage::Force,
    reads: &["x", "rho", "temperature"],
    writes: &["heat_rate"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// The same where it also writes the part from walls and sources.
pub static CONDUCTION_INPUT: PassSpec =
    PassSpec { name: "heat.conduction", writes: &["heat_rate", "heat_input"], ..CONDUCTION };

/// The conduction pass on the CPU, over the step's neighbour lists.
#[derive(Debug)]
pub struct Conduction;

impl CpuPass for Conduction {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| {
            if cx.attrs.has("material") { conduction::<true, _>(cx, s) } else { conduction::<false, _>(cx, s) }
        })
    }
}

/// The loop, specialised on whether the scene has several materials (one material
/// reads no index) and whether it is periodic.
fn conduction<const MULTI: bool, S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let hc: &HeatConsts = model.consts();
    let materials = &model.materials;
    let count = materials.len();
    let walls = &model.wall_particles;
    let h = 0.5 * k.support();
    let eps_h2 = 0.01 * h * h;
    let wall_t: Vec<Option<Real>> = walls.positions.iter().map(|&x| hc.wall_temperature(x)).collect();
    let rate_h = cx.attrs.handle::<Real>("heat_rate");
    let mut rate = cx.attrs.take(rate_h);
    let input_h = cx.attrs.find::<Real>(super::phase::HEAT_INPUT.name);
    let mut input = input_h.map(|h| cx.attrs.take(h));
    let attrs = &*cx.attrs;
    let (pos, rho, temp) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Real>("rho")),
        attrs.get(attrs.handle::<Real>("temperature")),
    );
    let mat: &[u32] = if MULTI { attrs.get(attrs.handle::<u32>("material")) } else { &[] };
    let material = |i: usize| if MULTI { mat[i] as usize } else { 0 };
    // dT/dt of particle `n` of chunk `c`, and its part from walls and sources.
    let particle = |c: usize, n: usize, nb: &crate::cpu::neighbors::ChunkNeighbors| -> (Real, Real) {
        let i = c * CHUNK + n;
        let (xi, rho_i, ti, ma) = (pos[i], rho[i], temp[i], material(i));
        let mut sum = 0.0;
        for &j in nb.fluid(n) {
            let j = j as usize;
            let r2 = sep.between(xi, pos[j]).length_squared();
            if r2 == 0.0 {
                continue;
            }
            let mb = material(j);
            let m = materials.get(mb).mass;
            let f = k.pair_factor(r2.sqrt(), eps_h2);
            sum += m / rho[j] * hc.pair_conductivity[ma * count + mb] * (ti - temp[j]) * f;
        }
        let psi = &walls.psi[ma];
        let rho0 = materials.get(ma).rest_density;
        let k_wall = hc.pair_conductivity[ma * count + ma];
        let mut outside = 0.0;
        for &b in nb.walls(n) {
            let b = b as usize;
            let Some(tb) = wall_t[b] else { continue };
            let r2 = sep.between(xi, walls.positions[b]).length_squared();
            if r2 == 0.0 {
                continue;
            }
            let f = k.pair_factor(r2.sqrt(), eps_h2);
            let term = psi[b] / rho0 * k_wall * 2.0 * (ti - tb) * f;
            sum += term;
            outside += term;
        }
        let source = hc.source(xi, rho_i, materials.get(ma).mass);
        let heat = rho_i * hc.capacity[ma];
        ((sum + source) / heat, (outside + source) / heat)
    };
    let chunks = rate.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate();
    match input.as_mut() {
        None => chunks.for_each(|(c, (out, nb))| {
            for (n, out) in out.iter_mut().enumerate() {
                *out = particle(c, n, nb).0;
            }
        }),
        Some(input) => chunks.zip(input.par_chunks_mut(CHUNK)).for_each(|((c, (out, nb)), from)| {
            for (n, (out, from)) in out.iter_mut().zip(from.iter_mut()).enumerate() {
                (*out, *from) = particle(c, n, nb);
            }
        }),
    }
    if let (Some(h), Some(input)) = (input_h, input) {
        cx.attrs.put(h, input);
    }
    cx.attrs.put(rate_h, rate);
}
