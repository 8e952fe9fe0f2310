//! # floe-engine
//!
//! Floe's simulation core, usable without any network code: offline runs,
//! tests and benchmarks link only this crate.
//!
//! How a scene flows through it:
//! ```text
//! scene (TOML/JSON/preset + overrides) ──scene::load──► Scene (validated)
//!     ──Model::build (core, scheme, modules)──► Model (materials, attributes, plan, channels)
//!     ──CpuBackend::new──► Backend ──Simulation::step (the scheme's stages)──► StepReport | Halted
//!     ──Simulation::read──► Particles ──floe_proto::export──► VTK / CSV
//! ```
//!
//! Modules:
//! - [`scene`]: the scene spec (one serde definition, JSON Schema), presets,
//!   loading with overrides, validation with field paths, live settings.
//! - [`model`]: a scene resolved into what a backend steps, built by the core, the
//!   scheme and the scene's modules through a `ModelBuilder`.
//! - [`attrs`], [`materials`], [`plan`], [`channels`]: the core's declarations: typed
//!   attribute columns, the material table, the pass plan, the channels clients stream.
//! - [`scheme`], [`module`]: what a pressure solver and a physics module are;
//!   [`schemes`] (WCSPH, DFSPH) and [`modules`] (fluid, heat, snow, snowfall): those shipped,
//!   listed in [`registry`], the only place that names them.
//! - [`quantities`]: what modules share (the per-particle viscosity and its factor),
//!   claimed by modules and resolved by the core; [`viscosity`]: that viscosity's
//!   force, explicit or implicit.
//! - [`mesh`]: bodies from OBJ and STL meshes, checked and filled with particles.
//! - [`maps`]: many-to-many index maps between spaces (clusters and their
//!   particles) with gathers and segmented sums; [`position_solve`]: modules'
//!   iterative solves over predicted positions; [`population`]: particles born and
//!   removed while a scene runs.
//! - [`math`], [`kernel`], [`neighbors`], [`periodic`]: numeric types, SPH kernels, the
//!   uniform grid, periodic domains (minimum-image pairs).
//! - [`boundary`], [`sampling`]: wall particles and constraints, particle lattices;
//!   [`terrain`]: heightfield ground (procedural or PNG) with Coulomb friction.
//! - [`clock`], [`timestep`], [`guard`]: the step control, adaptive dt and the
//!   stability guard with the modules' bounds.
//! - [`backend`], [`cpu`]: the backend trait and the rayon CPU backend.
//! - [`simulation`], [`summary`]: a running scene, its measures and run summary.
//! - [`snapshot`]: a scene's full state as bytes, restored bit for bit.
//! - [`quantize`]: positions on a frame's quantisation grid.
//! - [`validation`]: reference solutions, error measures, the case registry.

pub mod attrs;
pub mod backend;
pub mod boundary;
pub mod channels;
pub mod clock;
pub mod cpu;
pub mod guard;
pub mod kernel;
pub mod maps;
pub mod materials;
pub mod math;
pub mod mesh;
pub mod model;
pub mod module;
pub mod modules;
pub mod neighbors;
pub mod overburden;
pub mod periodic;
pub mod plan;
pub mod population;
pub mod position_solve;
pub mod quantities;
pub mod quantize;
pub mod registry;
pub mod sampling;
pub mod scene;
pub mod scheme;
pub mod schemes;
pub mod simulation;
pub mod snapshot;
pub mod summary;
pub mod terrain;
pub mod timestep;
pub mod validation;
pub mod viscosity;

pub use backend::{Backend, Particles, StepReport};
pub use guard::Halted;
pub use simulation::Simulation;
