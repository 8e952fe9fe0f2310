//! δ-SPH (`solver.delta_sph`; see [`super::spec::DeltaSph`] for the equations and
//! their papers): the density's rate from the continuity equation plus the
//! density diffusion, into `drho`, then `rho += dt drho`. The density pass then
//! only finds neighbours.
//!
//! Both passes run after the drift, with the velocity the drift moved the
//! particles with: the density is integrated as the positions are (symplectic
//! Euler's `x += dt v(n+1)`, leap-frog's drift with the half-step velocity), so the
//! pair density-velocity oscillates without growing. A rate taken with the
//! velocity before the kick (explicit Euler for that pair) made a resting column
//! blow up within 0.04 s.
//!
//! Why: a summed density is a function of where the particles are, so a fluid at
//! rest whose particles are not on a perfect lattice carries a density noise of
//! about 0.05 % that does not shrink with resolution, and the stiff equation of
//! state turns it into pressure noise of 5 % (L2) of the hydrostatic pressure at the
//! usual Mach number (docs/validation/hydrostatic). An integrated density starts
//! smooth and the diffusion keeps it so.

use super::WcsphConsts;
use super::eos::Eos;
use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role};
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::model::ModelBuilder;
use crate::model::core_attrs::RHO_INTEGRATED;
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// The density's rate (kg/(m^3 s)) of the last drift.
pub static DRHO: AttrSpec = AttrSpec {
    name: "drho",
    elem: Elem::F32,
    unit: "kg/(m^3 s)",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: "wcsph",
    about: "Rate of change of the density: continuity equation plus diffusion.",
};

/// `drho` from the continuity equation and the diffusion.
pub static CONTINUITY: PassSpec = PassSpec {
    name: "wcsph.continuity",
    module: "wcsph",
    stage: Stage::Drift,
    reads: &["x", "v", "rho"],
    writes: &["drho"],
    accumulates: &[],
    tolerance: 1e-4,
};

/// `rho += dt drho`.
pub static INTEGRATE: PassSpec = PassSpec {
    name: "wcsph.integrate_density",
    module: "wcsph",
    stage: Stage::Drift,
    reads: &["drho"],
    writes: &[],
    accumulates: &["rho"],
    tolerance: 1e-6,
};

/// The constants of the pass.
#[derive(Debug, Clone, PartialEq)]
pub struct DeltaConsts {
    /// `2 delta h c_a` (m^2/s) of each material, the diffusion's coefficient with the
    /// Laplacian's 2 and the fluid's own speed of sound
    /// ([`crate::materials::EquationOfState::sound_speed`]).
    pub coefficient: Vec<Real>,
    /// `0.01 h^2` (m^2), which keeps the Laplacian finite at small separations.
    pub eta2: Real,
    /// `rho0 g / c^2` of each material (kg/m^4): the hydrostatic density
    /// difference of two particles is this dotted with their separation.
    pub hydrostatic: Vec<Vec3>,
}

/// Declares the integrated density, its rate and the passes; returns the passes'
/// constants. Each particle starts at the density its equation of state gives the
/// weight of the fluid above it ([`crate::overburden`]): a fluid at rest starts in balance
/// instead of falling onto its own compression and ringing.
pub fn build(b: &mut ModelBuilder, delta: Real, sound_speed: Real, eos: &[Eos]) -> DeltaConsts {
    let rest: Vec<Real> = b.materials().iter().map(|m| m.rest_density).collect();
    let g: Vec3 = b.scene.gravity.into();
    let at_rest = crate::overburden::at_rest(b);
    let rho = at_rest.pressure.iter().zip(&at_rest.material).map(|(&p, &m)| eos[m as usize].density(p));
    b.redeclare(&RHO_INTEGRATED, Column::F32(rho.collect()));
    b.replace_pass("core.density", &crate::cpu::core::NEIGHBOURS);
    b.zeros(&DRHO);
    b.pass(&CONTINUITY);
    b.pass(&INTEGRATE);
    let h = 0.5 * b.kernel.support();
    DeltaConsts {
        coefficient: b.materials().iter().map(|m| 2.0 * delta * h * m.eos.sound_speed(sound_speed)).collect(),
        eta2: 0.01 * h * h,
        hydrostatic: rest.iter().zip(eos).map(|(&r0, e)| g * (r0 / (e.sound_speed() * e.sound_speed()))).collect(),
    }
}

/// `rho += dt drho` on the CPU.
#[derive(Debug)]
pub struct Integrate;

impl CpuPass for Integrate {
    fn run(&self, cx: &mut CpuCx<'_>) {
        let (r, d) = (cx.attrs.handle::<Real>("rho"), cx.attrs.handle::<Real>("drho"));
        let dt = cx.dt;
        let mut rho = cx.attrs.take(r);
        rho.par_iter_mut().zip(cx.attrs.get(d).par_iter()).with_min_len(4096).for_each(|(rho, &d)| *rho += d * dt);
        cx.attrs.put(r, rho);
    }
}

/// The rate on the CPU.
#[derive(Debug)]
pub struct Continuity;

impl CpuPass for Continuity {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| continuity(cx, s))
    }
}

fn continuity<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let walls = &model.wall_particles;
    let materials = &model.materials;
    let dc = model.consts::<WcsphConsts>().delta.as_ref().expect("the pass runs only under δ-SPH");
    let d_h = cx.attrs.handle::<Real>("drho");
    let mut out = cx.attrs.take(d_h);
    let attrs = &*cx.attrs;
    let (pos, vel, rho) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
    );
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    out.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (out_c, nb))| {
        for (n, out) in out_c.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let (xi, vi, rho_i, ma) = (pos[i], vel[i], rho[i], material(i));
            let (m_i, hydro, coefficient) = (materials.get(ma).mass, dc.hydrostatic[ma], dc.coefficient[ma]);
            let (mut div, mut diffusion) = (0.0, 0.0);
            for &j in nb.fluid(n) {
                let j = j as usize;
                let x_ij = sep.between(xi, pos[j]);
                let r2 = x_ij.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let dw = k.dw_dr(r);
                div += (vi - vel[j]).dot(x_ij) * (dw / r);
                let mb = material(j);
                if mb == ma {
                    let v_j = materials.get(mb).mass / rho[j];
                    diffusion += v_j * (rho_i - rho[j] - hydro.dot(x_ij)) * (r * dw) / (r2 + dc.eta2);
                }
            }
            let psi = &walls.psi[ma];
            let mut wall = 0.0;
            for &b in nb.walls(n) {
                let b = b as usize;
                let x_ib = sep.between(xi, walls.positions[b]);
                let r2 = x_ib.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                wall += psi[b] * vi.dot(x_ib) * (k.dw_dr(r) / r);
            }
            *out = m_i * div + wall + coefficient * diffusion;
        }
    });
    cx.attrs.put(d_h, out);
}
