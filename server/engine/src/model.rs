//! A scene resolved into the numbers a backend steps: particle mass, kernel,
//! speed of sound, equation of state, initial particles and walls.
//!
//! Every backend builds from a [`Model`], so CPU and GPU start from identical
//! state and constants.

use crate::boundary::{BoundaryParticles, WallConstraint, lattice_sum};
use crate::eos::Eos;
use crate::kernel::Kernel;
use crate::math::{Aabb, Real, Vec3};
use crate::sampling::{fill_block, sample_boundary};
use crate::scene::{Boundary, Integrator, Scene, TimeStep};
use crate::viscosity::ViscosityModel;

/// Why a valid scene still cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum BuildError {
    /// A fluid block is smaller than one particle spacing.
    #[error("{path}: holds no particle at particle_spacing {spacing} m; make it larger or the spacing smaller")]
    EmptyBlock {
        /// Path of the block.
        path: String,
        /// The spacing (m).
        spacing: Real,
    },
    /// The speed of sound cannot be derived.
    #[error(
        "solver.speed_of_sound: cannot be derived (no gravity along the fluid's height and no initial velocity); set solver.speed_of_sound or solver.expected_max_speed"
    )]
    NoSoundSpeed,
    /// The backend cannot hold or run the scene (e.g. it exceeds a GPU's limits).
    #[error("backend: {0}")]
    Backend(String),
}

/// The fluid phase's resolved constants.
#[derive(Debug, Clone)]
pub struct FluidModel {
    /// Rest density rho0 (kg/m^3).
    pub rho0: Real,
    /// Particle mass (kg): `rho0 / sum_j W(x_ij)` over a full cubic lattice of
    /// the spacing, so summation gives exactly `rho0` in the initial interior.
    /// (`rho0 spacing^3` would not: poly6 at support 2 spacings sums ~10 % high on a
    /// lattice, and the Tait equation turns that into an explosion.)
    pub mass: Real,
    /// Speed of sound c (m/s).
    pub sound_speed: Real,
    /// Equation of state.
    pub eos: Eos,
    /// Viscosity model.
    pub viscosity: ViscosityModel,
    /// XSPH factor epsilon (0 = off).
    pub xsph: Real,
}

/// Everything a backend needs to start stepping a scene.
#[derive(Debug, Clone)]
pub struct Model {
    /// Particle spacing (m).
    pub spacing: Real,
    /// The kernel, with support `support_factor * spacing`.
    pub kernel: Kernel,
    /// The fluid.
    pub fluid: FluidModel,
    /// Gravity (m/s^2).
    pub gravity: Vec3,
    /// Integrator.
    pub integrator: Integrator,
    /// Time step control.
    pub time_step: TimeStep,
    /// Damping rate (1/s) and the time it ends (s).
    pub damping: (Real, f64),
    /// Largest compression allowed before halting.
    pub max_compression: Real,
    /// Largest speed allowed before halting (m/s).
    pub max_speed: Real,
    /// Particles leaving this box halt the scene.
    pub domain: Aabb,
    /// Initial fluid positions (m).
    pub positions: Vec<Vec3>,
    /// Initial fluid velocities (m/s).
    pub velocities: Vec<Vec3>,
    /// Walls.
    pub boundary: BoundaryParticles,
    /// The walls' non-penetration constraints.
    pub walls: Vec<WallConstraint>,
}

impl Model {
    /// Resolves a validated scene.
    pub fn build(scene: &Scene) -> Result<Model, BuildError> {
        let d = scene.particle_spacing;
        let kernel = Kernel::new(scene.solver.kernel, scene.solver.support_factor * d);
        let gravity = Vec3::from(scene.gravity);
        let mut positions = Vec::new();
        let mut velocities = Vec::new();
        let fluid_spec = &scene.fluids[0];
        let mut fluid_box: Option<Aabb> = None;
        for (j, block) in fluid_spec.blocks.iter().enumerate() {
            let pts = fill_block(block, d);
            if pts.is_empty() {
                return Err(BuildError::EmptyBlock { path: format!("fluids[0].blocks[{j}]"), spacing: d });
            }
            let b = Aabb::new(block.min.into(), block.max.into());
            fluid_box = Some(fluid_box.map_or(b, |f| f.union(b)));
            velocities.extend(std::iter::repeat_n(Vec3::from(block.velocity), pts.len()));
            positions.extend(pts);
        }
        let fluid_box = fluid_box.expect("validation requires a block");
        let walls: Vec<Vec3> = scene.boundaries.iter().flat_map(|b| sample_boundary(b, d)).collect();
        let wall_box = walls.iter().fold(fluid_box, |acc, &p| acc.union(Aabb::new(p, p)));
        let domain = match &scene.domain {
            Some(b) => Aabb::new(b.min.into(), b.max.into()),
            None => wall_box.expanded(kernel.support()),
        };

        let c = match scene.solver.speed_of_sound {
            Some(c) => c,
            None => {
                let v = match scene.solver.expected_max_speed {
                    Some(v) => v,
                    None => fall_speed(gravity, fluid_box, wall_box, &velocities),
                };
                if v <= 0.0 {
                    return Err(BuildError::NoSoundSpeed);
                }
                scene.solver.mach_factor * v
            }
        };
        let rho0 = fluid_spec.rest_density;
        let viscosity = ViscosityModel::new(fluid_spec.viscosity, rho0, c, 0.5 * kernel.support());
        let layers = scene.boundaries.iter().map(|b| match b {
            Boundary::Box { layers, .. } | Boundary::Plane { layers, .. } => *layers,
        });
        let layers = layers.max().unwrap_or(1);
        let boundary = BoundaryParticles::new(walls, &kernel, rho0, domain.union(wall_box), d, layers);
        Ok(Model {
            spacing: d,
            kernel,
            fluid: FluidModel {
                rho0,
                mass: rho0 / lattice_sum(&kernel, d, None),
                sound_speed: c,
                eos: Eos::new(fluid_spec.eos, rho0, c),
                viscosity,
                xsph: fluid_spec.xsph,
            },
            gravity,
            integrator: scene.solver.integrator,
            time_step: scene.solver.time_step,
            damping: (scene.solver.damping, scene.solver.damping_until as f64),
            max_compression: scene.guard.max_compression,
            max_speed: scene.guard.max_speed.unwrap_or(c),
            domain,
            positions,
            velocities,
            boundary,
            walls: scene.boundaries.iter().map(|b| WallConstraint::new(b, d)).collect(),
        })
    }

    /// Takes the tunable settings of `scene` (see [`crate::scene::tunable`]):
    /// gravity, viscosity, XSPH, time step control, damping and guard bounds.
    pub fn retune(&mut self, scene: &Scene) {
        let f = &scene.fluids[0];
        self.gravity = scene.gravity.into();
        self.fluid.viscosity =
            ViscosityModel::new(f.viscosity, self.fluid.rho0, self.fluid.sound_speed, 0.5 * self.kernel.support());
        self.fluid.xsph = f.xsph;
        self.time_step = scene.solver.time_step;
        self.damping = (scene.solver.damping, scene.solver.damping_until as f64);
        self.max_compression = scene.guard.max_compression;
        self.max_speed = scene.guard.max_speed.unwrap_or(self.fluid.sound_speed);
    }

    /// Number of fluid particles.
    pub fn particle_count(&self) -> usize {
        self.positions.len()
    }
}

/// `sqrt(2 g H)`, H the drop from the fluid's top to the lowest point of fluid
/// or walls along gravity, or the fastest initial velocity if larger.
fn fall_speed(gravity: Vec3, fluid: Aabb, walls: Aabb, velocities: &[Vec3]) -> Real {
    let g = gravity.length();
    let initial = velocities.iter().map(|v| v.length()).fold(0.0, Real::max);
    if g == 0.0 {
        return initial;
    }
    let down = gravity / g;
    let corners = |b: Aabb| {
        (0..8).map(move |i| {
            Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            )
        })
    };
    let top = corners(fluid).map(|p| p.dot(down)).fold(Real::INFINITY, Real::min);
    let bottom = corners(fluid).chain(corners(walls)).map(|p| p.dot(down)).fold(Real::NEG_INFINITY, Real::max);
    (2.0 * g * (bottom - top).max(0.0)).sqrt().max(initial)
}
