//! The fluid module's built-in scenes. Each is an ordinary [`Scene`] value, so
//! `--set` overrides and `floe schema` apply to them exactly as to files.

use super::spec::{Fluid, FluidBlock, Look, TaylorGreen, Viscosity};
use crate::kernel::KernelKind;
use crate::module::Preset;
use crate::scene::{Axis, Boundary, BoxRegion, Face, Scene, Solver};
use serde_json::json;

/// The presets, for the module registry.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "dam_break",
        about: "A water column collapsing in a tank (Koshizuka & Oka 1996): 21,952 particles.",
        scene: dam_break,
    },
    Preset {
        name: "hydrostatic",
        about: "Water at rest in a closed tank, settling to rho0 g (H - y) (Adami et al. 2012).",
        scene: hydrostatic,
    },
    Preset {
        name: "poiseuille",
        about: "Start-up flow between plates 1 m apart, periodic along them (Morris, Fox & Zhu 1997).",
        scene: poiseuille,
    },
    Preset {
        name: "taylor_green",
        about: "Taylor-Green vortices decaying in a periodic unit square at Re = 100 (a thin periodic slab).",
        scene: taylor_green,
    },
];

/// Plate distance L (m), kinematic viscosity (m^2/s) and driving force (m/s^2) of
/// the Poiseuille preset: Morris et al.'s flow scaled to a 1 m channel (L^2 / nu =
/// 1 s as theirs), steady peak velocity F L^2 / (8 nu) = 0.0125 m/s, Re = 0.0125.
pub const POISEUILLE: (f32, f32, f32) = (1.0, 1.0, 0.1);

/// Wavelength L (m), peak speed U (m/s) and kinematic viscosity (m^2/s) of the
/// Taylor-Green preset: Re = U L / nu = 100 (docs/validation/cases.md §4).
pub const TAYLOR_GREEN: (f32, f32, f32) = (1.0, 1.0, 0.01);

/// The Taylor-Green vortex on WCSPH (the preset until 2026-12-06): the transport
/// velocity's background pressure `2 rho0 c^2` (Adami et al. 2013) at the preset's
/// speed of sound, 10 m/s, keeps its particles spread evenly; without it the
/// vortices decay 40 % too fast (docs/validation/taylor-green).
pub const TAYLOR_GREEN_WCSPH: [&str; 2] =
    ["solver.method=\"wcsph\"", "solver.transport_velocity={\"background\":200000}"];

/// Column width a (m) of the dam break.
pub const DAM_BREAK_A: f32 = 0.5;

fn water(blocks: Vec<FluidBlock>, viscosity: Viscosity) -> Fluid {
    Fluid {
        name: "water".into(),
        rest_density: 1000.0,
        eos: Default::default(),
        viscosity,
        xsph: 0.0,
        look: Look::Water,
        blocks,
    }
}

/// A scene with its fluids: the module's section.
trait WithFluids {
    fn with_fluids(self, fluids: Vec<Fluid>) -> Self;
}

impl WithFluids for Scene {
    fn with_fluids(mut self, fluids: Vec<Fluid>) -> Self {
        self.sections.set(super::SECTION, &fluids);
        self
    }
}

fn closed_box(min: [f32; 3], max: [f32; 3]) -> Boundary {
    Boundary::Box { min, max, open: Vec::new(), layers: 1 }
}

/// Koshizuka & Oka (1996) / Martin & Moyce (1952) dam break: a water column
/// a wide and 2a high (a = 0.5 m), a/2 deep, against the left wall of a tank
/// 4a x 2.4a x a/2. Spacing a/28 gives 21,952 fluid particles.
///
/// DFSPH is its pressure solver, chosen by measurement: it reaches 0.5 s of this
/// flow in about a fifth of WCSPH's wall time, with a smaller surge-front error at
/// every resolution up to this one (docs/benchmarks.md, "Time to solution against
/// SPlisHSPlasH"; docs/validation/dam-break). The other presets keep WCSPH: at rest
/// DFSPH's pressure beside the walls is 1.6-2.7 times the hydrostatic one
/// (docs/validation/hydrostatic/NOTES.md), and it diverges on the periodic
/// Taylor-Green vortex (every case on both schemes: docs/validation/schemes/NOTES.md).
pub fn dam_break() -> Scene {
    let a = DAM_BREAK_A;
    Scene {
        name: "dam_break".into(),
        modules: vec!["fluid".into()],
        particle_spacing: a / 28.0,
        gravity: [0.0, -9.81, 0.0],
        boundaries: vec![closed_box([0.0; 3], [4.0 * a, 2.4 * a, 0.5 * a])],
        domain: None,
        periodic: Vec::new(),
        solver: Solver { method: "dfsph".into(), ..Solver::default() },
        guard: Default::default(),
        sections: Default::default(),
    }
    .with_fluids(vec![water(
        vec![FluidBlock::at_rest([0.0; 3], [a, 2.0 * a, 0.5 * a])],
        Viscosity::Artificial { alpha: 0.02 },
    )])
}

/// Water at rest in a closed tank 0.3 x 1.05 x 0.15 m, filled to H = 0.9 m
/// (the column height of Adami et al. 2012), damped for its first 0.5 s so it
/// settles; afterwards pressure should match `rho0 g (H - y)`. DFSPH with
/// conjugate-gradient solves (`solver.dfsph.solver = "cg"`) on Wendland's kernel:
/// its walls carry the fluid's hydrostatic pressure and its column keeps its
/// lattice, 1.1 % off at 0.025 m in 240 steps where WCSPH with δ-SPH (the preset
/// until 2026-12-06) is 1.3 % off in 3392, and its error falls with the spacing
/// (docs/validation/hydrostatic). Every extent is a whole number of each spacing the
/// case runs at (0.05, 0.0375, 0.025, 0.01875 m): a box's walls stretch their
/// lattice to fit its extent ([`crate::sampling`]), and side walls whose layers
/// drift against the fluid's by a spacing over the column held it 4-5 % above
/// hydrostatic (0.0375 m in a 1.0 m tank, docs/validation/schemes/CG.md).
/// Artificial viscosity 0.1 damps the column's slow sloshing within the settling time.
pub fn hydrostatic() -> Scene {
    Scene {
        name: "hydrostatic".into(),
        modules: vec!["fluid".into()],
        particle_spacing: 0.025,
        gravity: [0.0, -9.81, 0.0],
        boundaries: vec![closed_box([0.0; 3], [0.3, 1.05, 0.15])],
        domain: Some(BoxRegion { min: [-0.1, -0.1, -0.1], max: [0.4, 1.1, 0.25] }),
        periodic: Vec::new(),
        solver: Solver {
            method: "dfsph".into(),
            kernel: KernelKind::WendlandC2,
            damping: 5.0,
            damping_until: 0.5,
            ..Solver::default()
        }
        .with("dfsph", json!({ "solver": "cg" })),
        guard: Default::default(),
        sections: Default::default(),
    }
    .with_fluids(vec![water(
        vec![FluidBlock::at_rest([0.0; 3], [0.3, 0.9, 0.15])],
        Viscosity::Artificial { alpha: 0.1 },
    )])
}

/// Morris, Fox & Zhu (1997): plates at y = 0 and y = L, periodic along x and z
/// (0.4 L each, a whole number of spacings for L/10 to L/40), the fluid at rest,
/// driven by a body force along x from t = 0. Laplacian viscosity, two wall layers
/// (a full support), and a speed of sound 80 times the peak velocity: the flow is
/// bound by the viscous step limit, not by sound.
pub fn poiseuille() -> Scene {
    let (l, nu, force) = POISEUILLE;
    let w = 0.4 * l;
    Scene {
        name: "poiseuille".into(),
        modules: vec!["fluid".into()],
        particle_spacing: l / 20.0,
        gravity: [force, 0.0, 0.0],
        boundaries: vec![Boundary::Box {
            min: [0.0; 3],
            max: [w, l, w],
            open: vec![Face::MinusX, Face::PlusX, Face::MinusZ, Face::PlusZ],
            layers: 2,
        }],
        domain: Some(BoxRegion { min: [0.0, -0.25 * l, 0.0], max: [w, 1.25 * l, w] }),
        periodic: vec![Axis::X, Axis::Z],
        solver: Solver { speed_of_sound: Some(1.0), ..Solver::default() },
        guard: Default::default(),
        sections: Default::default(),
    }
    .with_fluids(vec![water(vec![FluidBlock::at_rest([0.0; 3], [w, l, w])], Viscosity::Laplacian { nu })])
}

/// Taylor & Green (1937) vortices in a box periodic along every axis: the unit
/// square in x-y, 0.15 m deep in z, no walls, no gravity, Laplacian viscosity for
/// Re = 100. The kernel's support is 3 spacings (h = 1.5 spacings), which keeps the
/// density sum of the sheared lattice quieter than the default 2; the depth is two
/// supports at L/40 and a whole number of spacings at L/40, L/60 and L/80. Stepped
/// by DFSPH's conjugate gradients, whose particle shift in the closed box
/// (`solver.dfsph.shift`) keeps the particles spread evenly as the vortices shear
/// the lattice (decay rate within 0.45 % at L/40 in 401 steps; 57 % too fast
/// without the shift). [`TAYLOR_GREEN_WCSPH`] runs it on WCSPH as it was until
/// 2026-12-06 (1.0 % in 1125 steps; docs/validation/taylor-green). The speed of
/// sound, 10 times the peak speed, is WCSPH's.
pub fn taylor_green() -> Scene {
    let (l, u, nu) = TAYLOR_GREEN;
    let size = [l, l, 0.15 * l];
    let block = FluidBlock {
        taylor_green: Some(TaylorGreen { amplitude: u, wavelength: l }),
        ..FluidBlock::at_rest([0.0; 3], size)
    };
    Scene {
        name: "taylor_green".into(),
        modules: vec!["fluid".into()],
        particle_spacing: l / 40.0,
        gravity: [0.0; 3],
        boundaries: Vec::new(),
        domain: Some(BoxRegion { min: [0.0; 3], max: size }),
        periodic: vec![Axis::X, Axis::Y, Axis::Z],
        solver: Solver {
            method: "dfsph".into(),
            support_factor: 3.0,
            speed_of_sound: Some(10.0 * u),
            ..Solver::default()
        }
        .with("dfsph", json!({ "solver": "cg" })),
        guard: Default::default(),
        sections: Default::default(),
    }
    .with_fluids(vec![water(vec![block], Viscosity::Laplacian { nu })])
}
