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
use crate::modules::ModuleDef;
use crate::periodic::Periodicity;
use crate::plan::{PassSpec, Plan};
use crate::sampling::sample_boundary;
use crate::scene::{Boundary, Integrator, Scene, TimeStep};
use crate::schemes::SchemeDef;
use crate::terrain::HeightGrid;
use crate::terrain::source::rasterise_all;
use std::any::{Any, TypeId};
use std::sync::Arc;

/// Why a valid scene still cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum BuildError {
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
        space: PARTICLES,
        module: "core",
        about: "Particle position.",
    };
    /// Velocity.
    pub const V: AttrSpec = AttrSpec { name: "v", unit: "m/s", about: "Particle velocity.", ..X };
    /// Acceleration of the last evaluation (state: leap-frog's first half-kick uses it).
    pub const A: AttrSpec = AttrSpec { name: "a", unit: "m/s^2", about: "Acceleration of the last evaluation.", ..X };
    /// Stable particle id.
    pub const ID: AttrSpec =
        AttrSpec { name: "id", elem: Elem::U32, unit: "", about: "Stable id of the particle in each slot.", ..X };
    /// Slot of each id (the inverse of `id`), rebuilt by every sort.
    pub const SLOT: AttrSpec = AttrSpec {
        name: "slot_of",
        elem: Elem::U32,
        unit: "",
        role: Role::Derived,
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
        about: "Density by summation.",
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
    /// Spaces and attributes.
    pub layout: Layout,
    /// The passes of a step, in order.
    pub plan: Plan,
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
    /// core's (gravity, time step, damping, guard), then each module's. Attributes
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

    /// Number of SPH particles.
    pub fn particle_count(&self) -> usize {
        self.layout.count(PARTICLES)
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

/// Particles a module adds to the particle space.
#[derive(Debug, Default)]
struct NewParticles {
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    materials: Vec<u32>,
    /// Bounding box of the blocks they were sampled from.
    bounds: Option<Aabb>,
    /// Their largest initial speed (m/s).
    fastest: Real,
}

/// Assembles a [`Model`]: the core, then the scene's scheme and modules add their
/// particles, materials, attributes, passes, channels and constants.
#[derive(Debug)]
pub struct ModelBuilder<'s> {
    /// The scene being built.
    pub scene: &'s Scene,
    /// The kernel.
    pub kernel: Kernel,
    spacing: Real,
    materials: Vec<Material>,
    particles: NewParticles,
    walls: Vec<Vec3>,
    /// Each boundary's rasterised heights (terrains only).
    grids: Vec<Option<Arc<HeightGrid>>>,
    sound_speed: Option<Real>,
    layout: Layout,
    passes: Vec<&'static PassSpec>,
    channels: Vec<ChannelSpec>,
    sets: Vec<SetSpec>,
    bounds: Vec<Bound>,
    consts: Consts,
}

impl<'s> ModelBuilder<'s> {
    fn new(scene: &'s Scene) -> Result<Self, BuildError> {
        let d = scene.particle_spacing;
        let grids: Vec<Option<Arc<HeightGrid>>> =
            rasterise_all(scene).map_err(BuildError::Terrain)?.into_iter().map(|g| g.map(Arc::new)).collect();
        let sample =
            |(b, g): (&Boundary, &Option<Arc<HeightGrid>>)| sample_boundary(b, d, scene.periodic_axes(), g.as_deref());
        Ok(Self {
            scene,
            kernel: Kernel::new(scene.solver.kernel, scene.solver.support_factor * d),
            spacing: d,
            materials: Vec::new(),
            particles: NewParticles::default(),
            walls: scene.boundaries.iter().zip(&grids).flat_map(sample).collect(),
            grids,
            sound_speed: None,
            layout: Layout::default(),
            passes: Vec::new(),
            channels: Vec::new(),
            bounds: Vec::new(),
            sets: vec![crate::channels::PARTICLE_SET],
            consts: Consts::default(),
        })
    }

    /// Adds a material; returns its index.
    pub fn material(&mut self, name: &str, kind: crate::materials::MaterialKind, rest_density: Real) -> u32 {
        let mass = rest_density / lattice_sum(&self.kernel, self.spacing, None);
        self.materials.push(Material { name: name.into(), kind, rest_density, mass });
        (self.materials.len() - 1) as u32
    }

    /// Adds particles of material `material` at `positions` with `velocities`, sampled
    /// from `bounds` (for the default domain and the fall height of the sound speed).
    /// Those a terrain buries are dropped.
    pub fn particles(&mut self, material: u32, mut positions: Vec<Vec3>, mut velocities: Vec<Vec3>, bounds: Aabb) {
        crate::terrain::drop_buried(&self.grids, self.spacing, &mut positions, &mut velocities);
        let p = &mut self.particles;
        p.materials.extend(std::iter::repeat_n(material, positions.len()));
        p.fastest = velocities.iter().map(|v| v.length()).fold(p.fastest, Real::max);
        p.positions.extend(positions);
        p.velocities.extend(velocities);
        p.bounds = Some(p.bounds.map_or(bounds, |b| b.union(bounds)));
    }

    /// The speed of sound: `solver.speed_of_sound`, or `mach_factor` times the expected
    /// largest speed (`solver.expected_max_speed`, else the fall speed `sqrt(2 g H)` of
    /// the particles added so far, or their fastest initial velocity).
    pub fn sound_speed(&mut self) -> Result<Real, BuildError> {
        if let Some(c) = self.sound_speed {
            return Ok(c);
        }
        let s = &self.scene.solver;
        let c = match s.speed_of_sound {
            Some(c) => c,
            None => {
                let v = match s.expected_max_speed {
                    Some(v) => v,
                    None => {
                        let fluid = self.particles.bounds.unwrap_or(Aabb::new(Vec3::ZERO, Vec3::ZERO));
                        let walls = self.walls.iter().fold(fluid, |acc, &p| acc.union(Aabb::new(p, p)));
                        fall_speed(self.scene.gravity.into(), fluid, walls, self.particles.fastest)
                    }
                };
                if v <= 0.0 {
                    return Err(BuildError::NoSoundSpeed);
                }
                s.mach_factor * v
            }
        };
        self.sound_speed = Some(c);
        Ok(c)
    }

    /// The materials added so far.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// Declares index space `name` with `count` elements.
    pub fn space(&mut self, name: &'static str, count: usize) {
        self.layout.spaces.retain(|(s, _)| *s != name);
        self.layout.spaces.push((name, count));
    }

    /// Elements of `space`.
    pub fn count(&self, space: &str) -> usize {
        self.layout.count(space)
    }

    /// Allocates attribute `spec` with its initial values.
    pub fn attr(&mut self, spec: &'static AttrSpec, initial: Column) {
        assert_eq!(initial.elem(), spec.elem, "attribute {}: initial values of another type", spec.name);
        assert_eq!(initial.len(), self.count(spec.space), "attribute {}: one value per element", spec.name);
        assert!(self.layout.spec(spec.name).is_none(), "attribute {} declared twice", spec.name);
        self.layout.attrs.push((spec, initial));
    }

    /// The initial values of attribute `name`, if allocated (a module deriving its own
    /// initial state from the particles' positions or materials).
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.layout.attrs.iter().find(|(s, _)| s.name == name).map(|(_, c)| c)
    }

    /// Allocates attribute `spec`, zeroed.
    pub fn zeros(&mut self, spec: &'static AttrSpec) {
        let n = self.count(spec.space);
        self.attr(spec, Column::zeros(spec.elem, n));
    }

    /// Adds a pass to the plan.
    pub fn pass(&mut self, spec: &'static PassSpec) {
        self.passes.push(spec);
    }

    /// Offers a channel.
    pub fn channel(&mut self, spec: ChannelSpec) {
        self.channels.push(spec);
    }

    /// Adds a range a state attribute must stay in (the guard halts the scene otherwise).
    pub fn bound(&mut self, bound: Bound) {
        self.bounds.push(bound);
    }

    /// Offers a particle set (besides the SPH particles) to frames.
    pub fn set(&mut self, spec: SetSpec) {
        self.sets.push(spec);
    }

    /// Stores a module's constants (one value per type).
    pub fn set_consts<T: Any + Send + Sync>(&mut self, value: T) {
        set(&mut self.consts, value);
    }

    /// Runs the scheme and the modules, then assembles the model.
    fn finish(mut self) -> Result<Model, BuildError> {
        let scene = self.scene;
        let scheme = crate::schemes::of(scene);
        let modules = crate::modules::of(scene);
        for m in &modules {
            (m.particles)(scene, &mut self)?;
        }
        let d = self.spacing;
        let n = self.particles.positions.len();
        let fluid_box = self.particles.bounds.unwrap_or(Aabb::new(Vec3::ZERO, Vec3::ZERO));
        let wall_box = self.walls.iter().fold(fluid_box, |acc, &p| acc.union(Aabb::new(p, p)));
        let domain = match &scene.domain {
            Some(b) => Aabb::new(b.min.into(), b.max.into()),
            None => wall_box.expanded(self.kernel.support()),
        };
        let periodic = Periodicity::new(domain, scene.periodic_axes());
        if periodic.any() {
            for x in &mut self.particles.positions {
                *x = periodic.wrap(*x);
            }
        }
        self.core_layout(n);
        (scheme.build)(scene, &mut self)?;
        for m in &modules {
            (m.build)(scene, &mut self)?;
        }
        let layers = scene.boundaries.iter().map(|b| match b {
            Boundary::Box { layers, .. } | Boundary::Plane { layers, .. } => *layers,
            Boundary::Terrain(t) => t.layers,
        });
        let rest: Vec<Real> = self.materials.iter().map(|m| m.rest_density).collect();
        let walls = std::mem::take(&mut self.walls);
        let wall_particles = BoundaryParticles::new(
            walls,
            &self.kernel,
            &rest,
            domain.union(wall_box),
            &periodic,
            d,
            layers.max().unwrap_or(1),
        );
        let names: Vec<&str> = self.layout.specs().map(|s| s.name).collect();
        let plan = Plan::build(std::mem::take(&mut self.passes), &names)?;
        let sound_speed = self.sound_speed;
        Ok(Model {
            spacing: d,
            kernel: self.kernel,
            gravity: scene.gravity.into(),
            integrator: scene.solver.integrator,
            time_step: scene.solver.time_step,
            damping: (scene.solver.damping, scene.solver.damping_until as f64),
            max_compression: scene.guard.max_compression,
            max_speed: scene.guard.max_speed.or(sound_speed).unwrap_or(Real::INFINITY),
            domain,
            periodic,
            sound_speed,
            materials: Materials::new(self.materials),
            wall_particles,
            wall_constraints: scene
                .boundaries
                .iter()
                .zip(&self.grids)
                .map(|(b, g)| WallConstraint::new(b, d, g.as_ref()))
                .collect(),
            scheme,
            modules,
            layout: self.layout,
            plan,
            channels: self.channels,
            bounds: self.bounds,
            sets: self.sets,
            consts: self.consts,
        })
    }

    /// The core's spaces, attributes, passes and channels.
    fn core_layout(&mut self, n: usize) {
        use core_attrs::*;
        let p = std::mem::take(&mut self.particles);
        self.space(PARTICLES, n);
        self.space(WALLS, self.walls.len());
        self.attr(&X, Column::Vec3(p.positions));
        self.attr(&V, Column::Vec3(p.velocities));
        self.zeros(&A);
        self.attr(&ID, Column::U32((0..n as u32).collect()));
        self.attr(&SLOT, Column::U32((0..n as u32).collect()));
        if self.materials.len() > 1 {
            self.attr(&MATERIAL, Column::U32(p.materials));
        }
        self.zeros(&RHO);
        self.pass(&crate::cpu::core::SORT);
        self.pass(&crate::cpu::core::DENSITY);
        self.channel(crate::channels::VELOCITY);
        self.channel(crate::channels::DENSITY);
        if self.materials.len() > 1 {
            self.channel(crate::channels::MATERIAL);
        }
        (self.particles.bounds, self.particles.fastest) = (p.bounds, p.fastest);
    }
}

/// `sqrt(2 g H)`, H the drop from the fluid's top to the lowest point of fluid
/// or walls along gravity, or the fastest initial speed `initial` if larger.
fn fall_speed(gravity: Vec3, fluid: Aabb, walls: Aabb, initial: Real) -> Real {
    let g = gravity.length();
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
