//! [`ModelBuilder`]: what the core, the scheme and each module add to a [`Model`]
//! while it is built, and the assembly of the model from it.

use super::*;
use crate::quantities::Resolution;

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
    /// What each module does with the quantities the modules share (resolved
    /// before any module builds).
    pub quantities: Resolution,
    scheme: &'static SchemeDef,
    spacing: Real,
    materials: Vec<Material>,
    particles: NewParticles,
    walls: Vec<Vec3>,
    /// Each boundary's rasterised heights (terrains only).
    grids: Vec<Option<Arc<HeightGrid>>>,
    sound_speed: Option<Real>,
    layout: Layout,
    passes: Vec<&'static PassSpec>,
    velocity_solves: Vec<crate::scheme::Iterate>,
    position_solves: Vec<crate::scheme::Iterate>,
    after_position_solves: Vec<crate::scheme::Iterate>,
    maps: Vec<&'static crate::maps::MapSpec>,
    domain: Option<Aabb>,
    /// Births and deaths: room reserved, emitters, whether passes remove particles.
    reserved: usize,
    emitters: Vec<crate::population::Emitter>,
    removal: bool,
    channels: Vec<ChannelSpec>,
    sets: Vec<SetSpec>,
    bounds: Vec<Bound>,
    consts: Consts,
}

impl<'s> ModelBuilder<'s> {
    pub(super) fn new(scene: &'s Scene) -> Result<Self, BuildError> {
        let d = scene.particle_spacing;
        let grids: Vec<Option<Arc<HeightGrid>>> =
            rasterise_all(scene).map_err(BuildError::Terrain)?.into_iter().map(|g| g.map(Arc::new)).collect();
        let sample =
            |(b, g): (&Boundary, &Option<Arc<HeightGrid>>)| sample_boundary(b, d, scene.periodic_axes(), g.as_deref());
        Ok(Self {
            scene,
            kernel: Kernel::on_lattice(scene.solver.kernel, scene.solver.support_factor * d, d),
            quantities: crate::quantities::resolution(scene),
            scheme: crate::scheme::of(scene),
            spacing: d,
            materials: Vec::new(),
            particles: NewParticles::default(),
            walls: scene.boundaries.iter().zip(&grids).flat_map(sample).collect(),
            grids,
            sound_speed: None,
            layout: Layout::default(),
            passes: Vec::new(),
            velocity_solves: Vec::new(),
            position_solves: Vec::new(),
            after_position_solves: Vec::new(),
            maps: Vec::new(),
            domain: None,
            reserved: 0,
            emitters: Vec::new(),
            removal: false,
            channels: Vec::new(),
            bounds: Vec::new(),
            sets: vec![crate::channels::PARTICLE_SET],
            consts: Consts::default(),
        })
    }

    /// Adds a material with its equation of state; returns its index.
    pub fn material(
        &mut self,
        name: &str,
        kind: crate::materials::MaterialKind,
        rest_density: Real,
        eos: crate::materials::EquationOfState,
        look: crate::materials::Look,
    ) -> u32 {
        let mass = rest_density / lattice_sum(&self.kernel, self.spacing, None);
        // The own materials are numbered in order; phases repeat a number.
        let settings = self.materials.iter().map(|m| m.settings + 1).max().unwrap_or(0);
        self.materials.push(Material { name: name.into(), kind, rest_density, eos, look, mass, settings });
        (self.materials.len() - 1) as u32
    }

    /// Adds a phase of material `of`, named `name`, of rest density `rest_density`
    /// (kg/m^3): a material its particles may change into at run time and back (see
    /// [`crate::materials`]). It has `of`'s particle mass, so a particle keeps its
    /// mass when it changes, and everything else of material `like` (kind, equation
    /// of state, look, the modules' per-material settings). Modules declare phases
    /// with their particles (`ModuleDef::particles`), so every module's build sees
    /// the whole table. Panics if `of` or `like` is not a material.
    pub fn phase(&mut self, of: u32, like: u32, name: &str, rest_density: Real) -> u32 {
        let (of, like) = (&self.materials[of as usize], &self.materials[like as usize]);
        let phase = Material { name: name.into(), rest_density, mass: of.mass, ..like.clone() };
        self.materials.push(phase);
        (self.materials.len() - 1) as u32
    }

    /// Makes material `material` a solid's (the particles of a solid module's
    /// bodies): they stream as the scene's `solid` set (`SetSpec::part`), and a
    /// phase declared like a fluid (what ice melts into) stays fluid.
    pub fn solidify(&mut self, material: u32) {
        self.materials[material as usize].kind = crate::materials::MaterialKind::Solid;
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

    /// The scene's scheme (built before its modules).
    pub fn scheme(&self) -> &'static SchemeDef {
        self.scheme
    }

    /// The domain (m): known once every module added its particles, so to the
    /// scheme's and the modules' `build`.
    pub fn domain(&self) -> Aabb {
        self.domain.expect("the domain is known when the scheme and the modules build")
    }

    /// The height of the ground at `(x, z)` (m) where a terrain covers it (the first
    /// such terrain's raster).
    pub fn ground_at(&self, x: Real, z: Real) -> Option<Real> {
        self.grids.iter().flatten().find(|g| g.covers(x, z)).map(|g| g.eval(x, z).0)
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

    /// Declares attribute `spec` anew in place of the one of the same name (a
    /// scheme that integrates what the core would derive: the density under δ-SPH).
    pub fn redeclare(&mut self, spec: &'static AttrSpec, initial: Column) {
        self.layout.attrs.retain(|(s, _)| s.name != spec.name);
        self.attr(spec, initial);
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

    /// Puts `spec` in the place of the pass called `name` (a scheme that does the
    /// core's work its own way: δ-SPH integrates the density the core would sum).
    pub fn replace_pass(&mut self, name: &str, spec: &'static PassSpec) {
        let at = self.passes.iter().position(|p| p.name == name).unwrap_or_else(|| panic!("no pass {name} to replace"));
        self.passes[at] = spec;
    }

    /// Adds a velocity solve run after every kick (its passes added with [`Self::pass`]).
    pub fn velocity_solve(&mut self, solve: crate::scheme::Iterate) {
        self.velocity_solves.push(solve);
    }

    /// Adds a position solve (its passes added with [`Self::pass`]), run where the
    /// scheme runs them ([`crate::position_solve::When`]); the first one brings the
    /// core's prediction and velocity update, and under
    /// [`crate::position_solve::When::BeforeDensitySolve`] the look-ahead
    /// ([`crate::position_solve`]).
    pub fn position_solve(&mut self, solve: crate::scheme::Iterate) {
        use crate::position_solve::{
            LOOK_AHEAD, LOOK_BACK, PREDICT, VELOCITY_FROM_POSITIONS, When, X_PREDICTED, X_START,
        };
        if self.position_solves.is_empty() {
            self.zeros(&X_PREDICTED);
            self.pass(&PREDICT);
            self.pass(&VELOCITY_FROM_POSITIONS);
            if self.scheme.position_solves == When::BeforeDensitySolve {
                self.zeros(&X_START);
                self.pass(&LOOK_AHEAD);
                self.pass(&LOOK_BACK);
            }
        }
        self.position_solves.push(solve);
    }

    /// Adds a velocity correction run after the position solves have moved the
    /// positions and the velocities followed (its passes added with
    /// [`Self::pass`]); needs a position solve.
    pub fn after_position_solves(&mut self, solve: crate::scheme::Iterate) {
        assert!(!self.position_solves.is_empty(), "{}: after the position solves, but there is none", solve.name);
        self.after_position_solves.push(solve);
    }

    /// Declares index map `map` (see [`crate::maps`]) with its segments' member
    /// lists: segment `s` holds the members (ids of `map.members`) `lists[s]`. The
    /// segment space is declared here, or must already have `lists.len()` elements.
    pub fn map(&mut self, map: &'static crate::maps::MapSpec, lists: &[Vec<u32>]) {
        let members = self.count(map.members);
        let structure = map.structure(lists, members);
        if self.layout.spaces.iter().any(|(s, _)| *s == map.segments) {
            assert_eq!(self.count(map.segments), lists.len(), "map {}: one list per segment", map.name);
        } else {
            self.space(map.segments, lists.len());
        }
        self.space(map.name, structure.memberships);
        self.space(map.by_member, members);
        for (spec, column) in structure.columns {
            self.attr(spec, column);
        }
        self.maps.push(map);
    }

    /// Reserves room for `extra` particles beyond those the scene starts with (see
    /// [`crate::population`]).
    pub fn reserve(&mut self, extra: usize) {
        self.reserved += extra;
    }

    /// Adds an emitter of particles, run after every step (see [`crate::population`]).
    pub fn emitter(&mut self, emitter: crate::population::Emitter) {
        self.emitters.push(emitter);
    }

    /// Declares that passes mark particles to remove in the core's `remove`
    /// attribute (allocated here), which the core removes after every step.
    pub fn removal(&mut self) {
        if !self.removal {
            self.removal = true;
            self.zeros(&crate::population::REMOVE);
        }
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

    /// The constants of type `T` a module stored so far, if any.
    pub fn consts<T: Any + Send + Sync>(&self) -> Option<&T> {
        self.consts.0.iter().find(|(t, _)| *t == TypeId::of::<T>()).and_then(|(_, v)| v.downcast_ref())
    }

    /// Runs the scheme and the modules, then assembles the model.
    pub(super) fn finish(mut self) -> Result<Model, BuildError> {
        let scene = self.scene;
        let scheme = self.scheme;
        let modules = crate::module::of(scene);
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
        self.domain = Some(domain);
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
        // A solid module's build makes its materials solid.
        self.parts();
        // The shared quantities' passes act on what the modules wrote.
        if let Some(how) = self.quantities.integration() {
            let scaled = self.quantities.scaled();
            crate::viscosity::enable(&mut self, how, scaled);
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
        let population = self.population(n)?;
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
            wall_constraints: wall_constraints(scene, &self.grids, d),
            scheme,
            modules,
            quantities: self.quantities,
            layout: self.layout,
            plan,
            velocity_solves: self.velocity_solves,
            position_solves: self.position_solves,
            after_position_solves: self.after_position_solves,
            maps: self.maps,
            population,
            channels: self.channels,
            bounds: self.bounds,
            sets: self.sets,
            consts: self.consts,
        })
    }

    /// Where the SPH particles include a solid's: the solid's particles as a set of
    /// their own, and the fluid's where there are fluid materials (a melting solid's
    /// phases are), after the SPH set, whose parts they are.
    fn parts(&mut self) {
        use crate::materials::MaterialKind::{Fluid, Solid};
        let has = |k| self.materials.iter().any(|m| m.kind == k);
        if has(Solid) {
            let parts = [Solid, Fluid].into_iter().filter(|&k| has(k)).map(crate::channels::SetSpec::part);
            self.sets.splice(1..1, parts);
        }
    }

    /// A scene whose particles are born or die, of `n` particles at first: its
    /// counters, the sort without `slot_of` (ids grow without bound), and no index
    /// map over its particles.
    fn population(&mut self, n: usize) -> Result<Option<crate::population::Population>, BuildError> {
        use crate::population::{COUNTERS, NEXT_ID, Population, SORT};
        if self.emitters.is_empty() && !self.removal {
            return Ok(None);
        }
        if let Some(m) = self.maps.iter().find(|m| m.sorted()) {
            return Err(BuildError::Backend(format!(
                "index map {} addresses particles by id through slot_of, which a scene whose particles are born or die has not",
                m.name
            )));
        }
        self.layout.attrs.retain(|(s, _)| s.name != core_attrs::SLOT.name);
        self.replace_pass(SORT.name, &SORT);
        self.space(COUNTERS, 1);
        self.attr(&NEXT_ID, Column::U32(vec![n as u32]));
        let capacity = n + self.reserved;
        Ok(Some(Population {
            capacity,
            emitters: std::mem::take(&mut self.emitters),
            removal: self.removal,
            next_id: n as u32,
        }))
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
        // Every terrain's node heights, one after another: the ground as it is now.
        let ground: Vec<Real> = self.grids.iter().flatten().flat_map(|g| g.heights.iter().copied()).collect();
        if !ground.is_empty() {
            self.space(crate::terrain::GROUND_SPACE, ground.len());
            self.attr(&crate::terrain::GROUND, Column::F32(ground));
        }
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

/// The walls' constraints, each terrain's reading the ground from its first node in
/// `ground_height` (the terrains' nodes one after another).
fn wall_constraints(scene: &Scene, grids: &[Option<Arc<HeightGrid>>], spacing: Real) -> Vec<WallConstraint> {
    let mut first = 0;
    let walls = scene.boundaries.iter().zip(grids).map(|(b, g)| WallConstraint::new(b, spacing, g.as_ref()));
    walls
        .map(|mut w| {
            if let WallConstraint::Terrain(t) = &mut w {
                t.first = first;
                first += t.grid.heights.len();
            }
            w
        })
        .collect()
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
