//! What a physics module is ([`ModuleDef`]), and the registry of them: those the
//! engine ships ([`crate::registry::MODULES`]) and any registered at run time. A
//! scene lists the modules it uses (`modules = ["fluid"]`); only those build anything.
//!
//! A module brings, through its definition: its scene section's validation (with
//! field paths), the particle counts a server checks before building, its
//! particles and materials, its attributes, passes, channels and constants (through
//! the [`ModelBuilder`]), its CPU passes, its live-tunable settings, its presets and
//! its time-step limit, its validation cases and stability battery. `floe presets`, `floe validate`, live parameters and the
//! viewer's sliders pick a module up from here with no edit elsewhere. Modules
//! couple only through quantities the core declares, never by calling each other.
//!
//! [`register`] adds a module at run time (a plugin or a test's own module); it is
//! then known to every scene loaded afterwards in this process.

use crate::cpu::CpuPass;
use crate::math::Real;
use crate::model::{BuildError, Model, ModelBuilder};
use crate::scene::Scene;
use crate::scene::sections::SectionDef;
use crate::scene::tunable::Tunable;
use crate::scene::validate::Checker;
use crate::validation::cases::Case;
use crate::validation::stability::StabilityCase;
use std::sync::RwLock;

/// A built-in scene.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// Name, as `floe run NAME` and `CreateScene{preset}` take it.
    pub name: &'static str,
    /// What it shows.
    pub about: &'static str,
    /// The scene.
    pub scene: fn() -> Scene,
}

/// A benchmark a module brings to `floe bench --case NAME`.
#[derive(Debug, Clone, Copy)]
pub struct BenchCase {
    /// Name, as `--case` takes it.
    pub name: &'static str,
    /// What it times.
    pub about: &'static str,
    /// How it runs.
    pub kind: BenchKind,
}

/// How a [`BenchCase`] runs.
#[derive(Debug, Clone, Copy)]
pub enum BenchKind {
    /// The dam break with these overrides, timed beside the dam break alone at each
    /// size (what the module adds to a fluid step).
    Beside(&'static [&'static str]),
    /// A preset sized to about the first `--particles` count and simulated for
    /// `--until` seconds; the table reports these measures of the module at the end.
    Run {
        /// The preset.
        preset: &'static str,
        /// Measures to report ([`ModuleDef::measures`] names).
        measures: &'static [&'static str],
        /// What the count counts, and how the preset is sized to it.
        size: BenchSize,
    },
}

/// How a [`BenchKind::Run`] preset is sized.
#[derive(Debug, Clone, Copy)]
pub enum BenchSize {
    /// Its SPH particles, by the particle spacing (their count goes as its cube).
    Particles,
    /// The elements of one of the module's spaces (the snowfall's flakes), by
    /// the overrides the function gives for a count.
    Space(&'static str, fn(usize) -> Vec<String>),
}

/// A module's section of a scene file: a key of the document the module owns,
/// parsed and validated by it.
#[derive(Debug, Clone, Copy)]
pub struct Section {
    /// Its key and type.
    pub def: SectionDef,
    /// What a scene that lists the module without the section is told, after the key
    /// (`at least one fluid is required`); `None` for a section that may be left out.
    pub missing: Option<&'static str>,
}

impl Section {
    /// Its key in the file (`fluids`, `heat`).
    pub fn key(&self) -> &'static str {
        self.def.key
    }
}

/// A physics module.
#[derive(Debug)]
pub struct ModuleDef {
    /// Name, as a scene's `modules` list has it.
    pub id: &'static str,
    /// What it simulates.
    pub about: &'static str,
    /// Modules a scene must also list to use this one.
    pub requires: &'static [&'static str],
    /// The module's section of a scene file, if it has one (then a scene with the
    /// section must list the module, and a listed module must have its section).
    pub section: Option<Section>,
    /// Checks the module's section, naming bad fields by path.
    pub validate: fn(&Scene, &mut Checker),
    /// Elements the module adds to each space, counted without building (the server's
    /// particle limit refuses a scene before it allocates anything).
    pub count: fn(&Scene) -> Vec<(&'static str, u64)>,
    /// Materials the module adds (another module's section may hold one entry per
    /// material: `heat.fluids`), counted without building.
    pub materials: fn(&Scene) -> usize,
    /// The module's claims on the quantities modules share
    /// ([`crate::quantities`]), from its section (valid when called).
    pub claims: fn(&Scene) -> Vec<crate::quantities::Claim>,
    /// Adds the module's materials and particles (run for every module before any
    /// [`ModuleDef::build`], so the core knows every particle first).
    pub particles: fn(&Scene, &mut ModelBuilder) -> Result<(), BuildError>,
    /// Adds the module's attributes, passes, channels and constants.
    pub build: fn(&Scene, &mut ModelBuilder) -> Result<(), BuildError>,
    /// Takes new tunable settings from the scene.
    pub retune: fn(&Scene, &mut Model),
    /// The settings that may change while a scene exists.
    pub tunables: &'static [Tunable],
    /// The module's CPU passes, by pass name.
    pub cpu: &'static [(&'static str, &'static dyn CpuPass)],
    /// Built-in scenes.
    pub presets: &'static [Preset],
    /// The largest stable time step the module allows (s), if it limits it, and the
    /// limit's name for messages.
    pub dt_limit: fn(&Model) -> Option<(&'static str, Real)>,
    /// Named values the module reports with a scene's statistics (read from its
    /// state; called a few times a second at most).
    pub measures: fn(&crate::Simulation) -> Vec<crate::simulation::Measure>,
    /// Validation cases against references (`floe validate`).
    pub cases: &'static [Case],
    /// Stiff and extreme scenes that must finish or halt with a reason.
    pub stability: &'static [StabilityCase],
    /// Benchmarks (`floe bench --case NAME`).
    pub bench: &'static [BenchCase],
}

static EXTRA: RwLock<Vec<&'static ModuleDef>> = RwLock::new(Vec::new());

/// Adds a module to the registry (after the built-in ones); registering one twice
/// changes nothing.
pub fn register(module: &'static ModuleDef) {
    let mut extra = EXTRA.write().expect("registry lock");
    if !crate::registry::MODULES.iter().chain(extra.iter()).any(|m| m.id == module.id) {
        extra.push(module);
    }
}

/// Every module, built-in first.
pub fn all() -> Vec<&'static ModuleDef> {
    crate::registry::MODULES.iter().copied().chain(EXTRA.read().expect("registry lock").iter().copied()).collect()
}

/// The module called `id`.
pub fn find(id: &str) -> Option<&'static ModuleDef> {
    all().into_iter().find(|m| m.id == id)
}

/// The modules `scene` lists, in registry order (unknown names are validation errors).
pub fn of(scene: &Scene) -> Vec<&'static ModuleDef> {
    all().into_iter().filter(|m| scene.modules.iter().any(|id| id == m.id)).collect()
}

/// Elements `scene`'s modules will create, per space, counted without building them.
pub fn counts(scene: &Scene) -> Vec<(&'static str, u64)> {
    let mut out: Vec<(&'static str, u64)> = Vec::new();
    for (space, n) in of(scene).iter().flat_map(|m| (m.count)(scene)) {
        match out.iter_mut().find(|(s, _)| *s == space) {
            Some(e) => e.1 = e.1.saturating_add(n),
            None => out.push((space, n)),
        }
    }
    out
}

/// Materials `scene`'s modules will add, counted without building them.
pub fn materials(scene: &Scene) -> usize {
    of(scene).iter().map(|m| (m.materials)(scene)).sum()
}

/// Every module's benchmarks.
pub fn bench_cases() -> Vec<BenchCase> {
    all().iter().flat_map(|m| m.bench.iter().copied()).collect()
}

/// Every preset of every module.
pub fn presets() -> Vec<Preset> {
    all().iter().flat_map(|m| m.presets.iter().copied()).collect()
}

/// Every module's section of the scene document.
pub fn sections() -> Vec<SectionDef> {
    all().iter().filter_map(|m| m.section.map(|s| s.def)).collect()
}

/// Every tunable setting of the core and of `scene`'s modules.
pub fn tunables(scene: &Scene) -> Vec<Tunable> {
    let modules = of(scene);
    crate::scene::tunable::CORE.iter().chain(modules.iter().flat_map(|m| m.tunables)).copied().collect()
}
