//! Viscosity that varies from particle to particle, a quantity of the core that
//! modules share ([`crate::quantities`]): the attribute `mu` (Pa s), which one
//! module per scene writes before the forces (the snow module's rheology from the
//! shear rate, the heat module's law from the temperature), the factor another
//! module may scale it by (`viscosity_shift`, the heat module's temperature shift
//! of a rheology), and the viscous force of those viscosities, explicit (the pass
//! below) or implicit ([`implicit`]). The core turns the path on ([`enable`]) from
//! the modules' claims, after every module has built.
//!
//! The force, `viscosity.force`, takes each pair's viscosity as `mu_i + mu_j`:
//! `a_i = sum_j m_j (mu_i + mu_j) / (rho_i rho_j) F_ij v_ij`,
//! `F_ij = x_ij . grad_i W_ij / (r_ij^2 + 0.01 h^2)` (Morris, Fox & Zhu 1997,
//! J. Comput. Phys. 136, eq. 8, with the per-particle viscosity of their variable-
//! viscosity form). It is the divergence of the stress `2 mu D` where the flow is
//! incompressible and the viscosity varies across the flow only (channel and
//! sheared layers); the pairwise difference couples every neighbour directly. The
//! divergence of a per-particle stress tensor (a gradient of a gradient) was
//! measured first: on the snow module's channel flows its stencil lets neighbouring
//! layers decouple in pairs (an odd-even mode no term damps), with velocity errors
//! of 20 % to 120 %.
//!
//! Each pair's term is antisymmetric, so momentum is conserved, and
//! `sum_i m_i v_i . a_i = -1/2 sum_ij m_i m_j (mu_i + mu_j) / (rho_i rho_j) |F_ij| |v_ij|^2`:
//! the force only ever dissipates kinetic energy, whatever the viscosities. A wall
//! particle b (pseudo-mass `psi_b`) is the mirror image of the fluid particle it acts
//! on: velocity `-v_i`, viscosity `mu_i`, density `rho_i` (no slip on the wall surface,
//! half a spacing in front of the first wall layer, instead of at the wall
//! particles), times the walls' shear factor (0: slip walls exert no shear). Every
//! term carries the lattice normalisation the conduction and the constant-viscosity
//! Laplacian carry ([`crate::kernel::Kernel::pair_lattice_scale`], about 1 % for the
//! cubic spline): without it the channel flows' velocities stood about 1 % off the
//! steady profiles at every resolution. The GPU's varying.wgsl adds the same terms
//! in the same order.

pub mod implicit;
mod settings;

pub use settings::{ViscousSolver, WallShear};

use crate::attrs::{AttrSpec, Elem, PARTICLES, Role};
use crate::channels::{ChannelSpec, Source};
use crate::cpu::neighbors::CHUNK;
use crate::cpu::{CpuCx, CpuPass};
use crate::math::{Real, Vec3};
use crate::model::{Model, ModelBuilder};
use crate::periodic::Separation;
use crate::plan::{PassSpec, Stage};
use rayon::prelude::*;

/// The module name of the viscosity's passes, attributes and channel: the core's
/// shared quantity, run after every module's passes of a stage (they act on what
/// the modules wrote).
pub const MODULE: &str = "viscosity";

/// Dynamic viscosity per particle (Pa s), the quantity [`crate::quantities::VISCOSITY`].
pub static MU: AttrSpec = AttrSpec {
    name: "mu",
    elem: Elem::F32,
    unit: "Pa s",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: MODULE,
    about: "Dynamic viscosity of the particle at its current state.",
};

/// The factor the module that sets `mu` multiplies it by, the quantity
/// [`crate::quantities::VISCOSITY_FACTOR`] (1 where no module scales it).
pub static FACTOR: AttrSpec = AttrSpec {
    name: "viscosity_shift",
    elem: Elem::F32,
    unit: "",
    role: Role::Derived,
    added_later: false,
    space: PARTICLES,
    module: MODULE,
    about: "Factor on the viscosity a module sets (a temperature shift of a rheology; 1 at its reference).",
};

/// The viscous force of the per-particle viscosities, added to the accelerations.
pub static FORCE: PassSpec = PassSpec {
    name: "viscosity.force",
    module: MODULE,
    stage: Stage::Force,
    reads: &["x", "v", "rho", "mu"],
    writes: &[],
    accumulates: &["a"],
    tolerance: 1e-4,
};

/// The viscosity channel, in scenes whose viscosity varies.
pub const CHANNEL: ChannelSpec = ChannelSpec {
    name: "viscosity",
    unit: "Pa s",
    components: 1,
    exact: false,
    set: crate::attrs::PARTICLES,
    module: MODULE,
    about: "Dynamic viscosity of the particle at its current state (shear rate, temperature).",
    source: Source::Attr("mu"),
};

/// How the per-particle viscosities act, as the module that sets them chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VaryingViscosity {
    /// 1 where walls hold the fluid at rest (no slip), 0 where they exert no shear.
    pub wall_shear: Real,
    /// The lattice normalisation of the pair sum ([`crate::kernel::Kernel::pair_lattice_scale`]),
    /// which every pair term carries (the force's and the implicit solve's).
    pub scale: Real,
}

impl VaryingViscosity {
    fn new(walls: WallShear, scale: Real) -> Self {
        Self { wall_shear: if walls == WallShear::NoSlip { 1.0 } else { 0.0 }, scale }
    }
}

/// How the module that sets the per-particle viscosity integrates its force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integration {
    /// Explicit or implicit, and the implicit solve's settings.
    pub solver: ViscousSolver,
    /// The walls' condition.
    pub walls: WallShear,
}

/// Turns per-particle viscosity on: allocates `mu` (which the setting module's own
/// pass writes before the forces), the factor if a module scales it, the viscous
/// force or the implicit solve, and the viscosity channel.
pub fn enable(b: &mut ModelBuilder, how: Integration, scaled: bool) {
    b.zeros(&MU);
    if scaled {
        b.zeros(&FACTOR);
    }
    match how.solver {
        ViscousSolver::Explicit => b.pass(&FORCE),
        ViscousSolver::Implicit { tolerance, max_iterations } => {
            b.space(implicit::SCALARS_SPACE, 4);
            for spec in implicit::ATTRS {
                b.zeros(spec);
            }
            for pass in implicit::PASSES {
                b.pass(pass);
            }
            b.velocity_solve(implicit::solve(tolerance, max_iterations));
        }
    }
    b.channel(CHANNEL);
    let scale = b.kernel.pair_lattice_scale(b.scene.particle_spacing);
    b.set_consts(VaryingViscosity::new(how.walls, scale));
}

/// Applies new settings of the module that sets the viscosity: the walls, and the
/// implicit solve's tolerance and iteration limit.
pub fn retune(model: &mut Model, how: Integration) {
    let c = *model.consts::<VaryingViscosity>();
    model.set_consts(VaryingViscosity::new(how.walls, c.scale));
    if let ViscousSolver::Implicit { tolerance, max_iterations } = how.solver {
        let solve = implicit::solve(tolerance, max_iterations);
        for s in model.velocity_solves.iter_mut().filter(|s| s.name == solve.name) {
            *s = solve;
        }
    }
}

/// Whether the viscosities are integrated implicitly (no viscous limit on dt).
pub fn is_implicit(model: &Model) -> bool {
    model.velocity_solves.iter().any(|s| s.name == implicit::NAME)
}

/// The core's CPU passes of the viscosity.
pub static CPU: &[(&str, &dyn CpuPass)] = &[
    ("viscosity.force", &Force),
    ("viscosity.implicit_diagonal", &implicit::Diagonal),
    ("viscosity.implicit_precondition", &implicit::Precondition),
    ("viscosity.implicit_product", &implicit::Product),
    ("viscosity.implicit_update", &implicit::Update),
    ("viscosity.implicit_direction", &implicit::Direction),
];

/// Checks a module's viscous solver settings under `path`.
pub fn validate_solver(c: &mut crate::scene::validate::Checker, path: &str, solver: ViscousSolver) {
    if let ViscousSolver::Implicit { tolerance, max_iterations } = solver {
        c.within(&format!("{path}.tolerance"), tolerance, 1e-7, 0.5);
        if !(1..=10_000).contains(&max_iterations) {
            c.fail(&format!("{path}.max_iterations"), format!("must be 1 to 10000, got {max_iterations}"));
        }
    }
}

/// `viscosity.force` on the CPU.
#[derive(Debug)]
pub struct Force;

impl CpuPass for Force {
    fn run(&self, cx: &mut CpuCx<'_>) {
        crate::with_separation!(&cx.model.periodic, |s| viscosity(cx, s))
    }
}

fn viscosity<S: Separation>(cx: &mut CpuCx<'_>, sep: S) {
    let model = cx.model;
    let k = &model.kernel;
    let VaryingViscosity { wall_shear, scale, .. } = *model.consts();
    let materials = &model.materials;
    let walls = &model.wall_particles;
    let eps_h2 = 0.01 * 0.25 * k.support() * k.support();
    let a_h = cx.attrs.handle::<Vec3>("a");
    let mut acc = cx.attrs.take(a_h);
    let attrs = &*cx.attrs;
    let (pos, vel, rho, mu) = (
        attrs.get(attrs.handle::<Vec3>("x")),
        attrs.get(attrs.handle::<Vec3>("v")),
        attrs.get(attrs.handle::<Real>("rho")),
        attrs.get(attrs.handle::<Real>("mu")),
    );
    let mat = attrs.find::<u32>("material").map(|m| attrs.get(m));
    let material = |i: usize| mat.map_or(0, |m| m[i] as usize);
    acc.par_chunks_mut(CHUNK).zip(&cx.nb.chunks).enumerate().for_each(|(c, (acc_c, nb))| {
        for (n, out) in acc_c.iter_mut().enumerate() {
            let i = c * CHUNK + n;
            let (xi, vi, mu_i, ma) = (pos[i], vel[i], mu[i], material(i));
            let inv_rho = 1.0 / rho[i];
            let mut a = Vec3::ZERO;
            for &j in nb.fluid(n) {
                let j = j as usize;
                let x_ij = sep.between(xi, pos[j]);
                let r2 = x_ij.length_squared();
                if r2 == 0.0 {
                    continue;
                }
                let f = k.pair_factor(r2.sqrt(), eps_h2);
                let m = materials.get(material(j)).mass;
                a += (vi - vel[j]) * (m * (mu_i + mu[j]) * inv_rho / rho[j] * f);
            }
            let psi = &walls.psi[ma];
            let mirror = vi * (4.0 * wall_shear * mu_i * inv_rho * inv_rho);
            for &b in nb.walls(n) {
                let b = b as usize;
                let r2 = sep.between(xi, walls.positions[b]).length_squared();
                if r2 == 0.0 {
                    continue;
                }
                a += mirror * (psi[b] * k.pair_factor(r2.sqrt(), eps_h2));
            }
            *out += a * scale;
        }
    });
    cx.attrs.put(a_h, acc);
}
