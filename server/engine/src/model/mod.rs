//! A scene resolved into what a backend steps: the core's constants (kernel,
//! gravity, domain, walls, materials), the attributes every index space holds with
//! their initial values ([`Layout`]), the pass [`Plan`], the channels, and each
//! module's own constants.
//!
//! [`Model::build`] runs the core, then the scheme and every module of the scene
//! in registry order, each adding what it needs through a [`ModelBuilder`]. Every
//! backend builds from a [`Model`], so CPU and GPU start from identical state and
//! constants.

use crate::attrs::{AttrSpec, Column, Elem, PARTICLES, Role, WALLS};
use crate::boundary::{BoundaryParticles, WallConstraint, lattice_sum};
use crate::channels::{ChannelSpec, SetSpec};
use crate::guard::Bound;
use crate::kernel::Kernel;
use crate::materials::{Material, Materials};
use crate::math::{Aabb, Real, Vec3};
use crate::module::ModuleDef;
use crate::periodic::Periodicity;
use crate::plan::{PassSpec, Plan};
use crate::sampling::sample_boundary;
use crate::scene::{Boundary, Integrator, Scene, TimeStep};
use crate::scheme::SchemeDef;
use crate::terrain::HeightGrid;
use crate::terrain::source::rasterise_all;
use std::any::{Any, TypeId};
use std::sync::Arc;

mod builder;
pub use builder::ModelBuilder;

/// Why a valid scene still cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum BuildError {
    /// A mesh cannot be used (named by its field and file).
    #[error("{0}")]
    Mesh(String),
    /// A block of particles is smaller than one particle spacing.
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
    /// The scene's passes do not form a plan.
    #[error("modules: {0}")]
    Plan(#[from] crate::plan::PlanError),
    /// A terrain's heights cannot be read (e.g. an asset never read from the assets directory).
    #[error("{0}")]
    Terrain(String),
    /// A setting cannot be used with the rest of the scene (named by its path).
    #[error("{0}")]
    Setting(String),
    /// The backend cannot hold or run the scene (e.g. it exceeds a GPU's limits).
    #[error("backend: {0}")]
    Backend(String),
}

/// Core attributes of the particle space.
pub mod core_attrs {
    use super::*;
    /// Position.
    pub const X: AttrSpec = AttrSpec {
        name: "x",
        elem: Elem::Vec3,
        unit: "m",
        role: Role::State,
        added_later: false,
        space: PARTICLES,
        module: "core",
        about: "Particle position.",
    };
    /// Velocity.
    pub const V: AttrSpec = AttrSpec { name: "v", unit: "m/s", about: "Particle velocity.", ..X };
    /// Acceleration of the last evaluation (state: leap-frog's first half-kick uses it).
    pub const A: AttrSpec = AttrSpec { name: "a", unit: "m/s^2", about: "Acceleration of the last evaluation.", ..X };
    /// The transport part of the acceleration, from the last evaluation: it moves
    /// particles in the drift, `x += dt (v + dt/2 a_transport)`, and never enters
    /// their velocity. Only in scenes whose scheme declares it (WCSPH's
    /// `solver.transport_velocity`); state, as `a` is, for leap-frog's next drift.
    pub const A_TRANSPORT: AttrSpec = AttrSpec {
        name: "a_transport",
        unit: "m/s^2",
        about: "Acceleration that moves particles without entering their velocity.",
        ..X
    };
    /// Stable particle id.
    pub const ID: AttrSpec =
        AttrSpec { name: "id", elem: Elem::U32, unit: "", about: "Stable id of the particle in each slot.", ..X };
    /// Slot of each id (the inverse of `id`), rebuilt by every sort.
    pub const SLOT: AttrSpec = AttrSpec {
        name: "slot_of",
        elem: Elem::U32,
        unit: "",
        role: Role::Derived,
        added_later: false,
        about: "Slot of each stable id.",
        ..X
    };
    /// Material index, stored only when the scene has more than one material.
    pub const MATERIAL: AttrSpec =
        AttrSpec { name: "material", elem: Elem::U32, unit: "", about: "Index in the material table.", ..X };
    /// SPH density.
    pub const RHO: AttrSpec = AttrSpec {
        name: "rho",
        elem: Elem::F32,
        unit: "kg/m^3",
        role: Role::Derived,
        added_later: false,
        about: "Density by summation.",
        ..X
    };
    /// SPH density integrated in time (a scheme's continuity equation, e.g. WCSPH's
    /// δ-SPH) in place of [`RHO`]: state, so it is sorted with its particles and
    /// saved in snapshots, and the density pass then only finds neighbours.
    pub const RHO_INTEGRATED: AttrSpec = AttrSpec {
        name: "rho",
        elem: Elem::F32,
        unit: "kg/m^3",
        about: "Density integrated by the continuity equation.",
        ..X
    };
}

/// The index spaces of a scene and the attributes they hold, with initial values.
#[derive(Debug, Clone, Default)]
pub struct Layout {
    /// Spaces and their element counts.
    pub spaces: Vec<(&'static str, usize)>,
    /// Attributes and their initial columns (moved out by the backend that takes them).
    pub attrs: Vec<(&'static AttrSpec, Column)>,
}

impl Layout {
    /// Elements of `space` (0 if the scene has no such space).
    pub fn count(&self, space: &str) -> usize {
        self.spaces.iter().find(|(s, _)| *s == space).map_or(0, |&(_, n)| n)
    }

    /// The declaration of attribute `name`.
    pub fn spec(&self, name: &str) -> Option<&'static AttrSpec> {
        self.attrs.iter().map(|(s, _)| *s).find(|s| s.name == name)
    }

    /// Every attribute's declaration.
    pub fn specs(&self) -> impl Iterator<Item = &'static AttrSpec> + '_ {
        self.attrs.iter().map(|(s, _)| *s)
    }

    /// The initial columns, taken out (the layout keeps the declarations).
    pub fn take_columns(&mut self) -> Vec<(&'static AttrSpec, Column)> {
        self.attrs.iter_mut().map(|(s, c)| (*s, std::mem::replace(c, Column::zeros(s.elem, 0)))).collect()
    }
}

/// Module constants, one value per type, shared cheaply when a model is cloned.
#[derive(Clone, Default)]
struct Consts(Vec<(TypeId, Arc<dyn Any + Send + Sync>)>);

impl std::fmt::Debug for Consts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} module constant sets", self.0.len())
    }
}

/// Everything a backend needs to start stepping a scene.
#[derive(Debug, Clone)]
pub struct Model {
    /// Particle spacing (m).
    pub spacing: Real,
    /// The kernel, with support `support_factor * spacing`.
    pub kernel: Kernel,
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
    /// Particles leaving this box halt the scene (on an open axis).
    pub domain: Aabb,
    /// The domain's periodic axes.
    pub periodic: Periodicity,
    /// The speed of sound (m/s), when the scheme or a module derived one.
    pub sound_speed: Option<Real>,
    /// The material table.
    pub materials: Materials,
    /// Wall particles (Akinci et al. 2012), sorted by their own grid.
    pub wall_particles: BoundaryParticles,
    /// The walls' non-penetration constraints.
    pub wall_constraints: Vec<WallConstraint>,
    /// Ranges the modules' state attributes must stay in.
    pub bounds: Vec<Bound>,
    /// The scheme stepping the scene.
    pub scheme: &'static SchemeDef,
    /// The scene's modules, in registry order.
    pub modules: Vec<&'static ModuleDef>,
    /// What each module does with the quantities the modules share.
    pub quantities: crate::quantities::Resolution,
    /// Spaces and attributes.
    pub layout: Layout,
    /// The passes of a step, in order.
    pub plan: Plan,
    /// The modules' velocity solves after each kick, in order
    /// ([`crate::scheme::velocity_solves`]).
    pub velocity_solves: Vec<crate::scheme::Iterate>,
    /// The modules' position solves, in order, run where the scheme says
    /// ([`crate::position_solve`]).
    pub position_solves: Vec<crate::scheme::Iterate>,
    /// The modules' velocity corrections run after the position solves, over the
    /// solved positions ([`crate::position_solve::run`]).
    pub after_position_solves: Vec<crate::scheme::Iterate>,
    /// The index maps ([`crate::maps`]).
    pub maps: Vec<&'static crate::maps::MapSpec>,
    /// Births and deaths, in a scene that has them ([`crate::population`]).
    pub population: Option<crate::population::Population>,
    /// The channels frames and exports can carry.
    pub channels: Vec<ChannelSpec>,
    /// The particle sets frames can carry.
    pub sets: Vec<SetSpec>,
    consts: Consts,
}

impl Model {
    /// Resolves a validated scene.
    pub fn build(scene: &Scene) -> Result<Model, BuildError> {
        ModelBuilder::new(scene)?.finish()
    }

    /// Takes the tunable settings of `scene` (see [`crate::scene::tunable`]): the
    /// core's (gravity, time step, damping, guard), then each module's, then the
    /// shared viscosity's integration. Attributes
    /// and passes may come or go (XSPH switched on); backends follow the layout.
    pub fn retune(&mut self, scene: &Scene) {
        self.gravity = scene.gravity.into();
        self.time_step = scene.solver.time_step;
        self.damping = (scene.solver.damping, scene.solver.damping_until as f64);
        self.max_compression = scene.guard.max_compression;
        self.max_speed = scene.guard.max_speed.or(self.sound_speed).unwrap_or(Real::INFINITY);
        (self.scheme.retune)(scene, self);
        for m in self.modules.clone() {
            (m.retune)(scene, self);
        }
        // The roles stay (the modules stay); the viscosity's integration may change.
        if let Some(how) = crate::quantities::resolution(scene).integration() {
            crate::viscosity::retune(self, how);
        }
    }

    /// The constants a module stored with [`ModelBuilder::set_consts`].
    pub fn consts<T: Any + Send + Sync>(&self) -> &T {
        self.consts
            .0
            .iter()
            .find(|(t, _)| *t == TypeId::of::<T>())
            .and_then(|(_, v)| v.downcast_ref())
            .unwrap_or_else(|| panic!("no constants of type {}", std::any::type_name::<T>()))
    }

    /// Replaces a module's constants (on retune).
    pub fn set_consts<T: Any + Send + Sync>(&mut self, value: T) {
        set(&mut self.consts, value);
    }

    /// Adds attribute `spec` (zeros) if the layout lacks it, with its pass; or, with
    /// `on` false, removes both: a setting that switches a feature on or off while the
    /// scene exists. Backends allocate or free to follow (see `Backend::retune`).
    pub fn toggle(&mut self, on: bool, spec: &'static AttrSpec, passes: &[&'static PassSpec]) {
        let has = self.layout.spec(spec.name).is_some();
        if on && !has {
            let n = self.layout.count(spec.space);
            self.layout.attrs.push((spec, Column::zeros(spec.elem, n)));
        } else if !on && has {
            self.layout.attrs.retain(|(s, _)| s.name != spec.name);
        }
        let mut list: Vec<&'static PassSpec> =
            self.plan.passes().iter().copied().filter(|p| !passes.iter().any(|q| q.name == p.name)).collect();
        if on {
            list.extend(passes);
        }
        let names: Vec<&str> = self.layout.specs().map(|s| s.name).collect();
        self.plan = Plan::build(list, &names).expect("a toggled feature keeps the plan valid");
    }

    /// Number of SPH particles (live ones, in a scene whose particles are born and die).
    pub fn particle_count(&self) -> usize {
        self.layout.count(PARTICLES)
    }

    /// Particles the scene can hold at once: its count, or its population's capacity.
    pub fn particle_capacity(&self) -> usize {
        self.population.as_ref().map_or(self.particle_count(), |p| p.capacity)
    }

    /// Sets the live count of the particle space (births and deaths, a restore).
    pub fn set_particle_count(&mut self, n: usize) {
        if let Some(s) = self.layout.spaces.iter_mut().find(|(s, _)| *s == PARTICLES) {
            s.1 = n;
        }
    }

    /// Whether the scene has module `id`.
    pub fn has_module(&self, id: &str) -> bool {
        self.modules.iter().any(|m| m.id == id)
    }
}

fn set<T: Any + Send + Sync>(consts: &mut Consts, value: T) {
    let id = TypeId::of::<T>();
    consts.0.retain(|(t, _)| *t != id);
    consts.0.push((id, Arc::new(value)));
}
