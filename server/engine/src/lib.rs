//! # floe-engine
//!
//! Floe's simulation core, usable without any network code: offline runs,
//! tests and benchmarks link only this crate.
//!
//! How a scene flows through it:
//! ```text
//! scene (TOML/JSON/preset + overrides) ──scene::load──► Scene (validated)
//!     ──Model::build──► Model (mass, kernel, c, particles, walls)
//!     ──CpuBackend::new──► Backend ──Simulation::step──► StepReport | Halted
//!     ──Simulation::read──► Particles ──floe_proto::export──► VTK / CSV
//! ```
//!
//! Modules:
//! - [`scene`]: the scene spec (one serde definition, JSON Schema), presets,
//!   loading with overrides, validation with field paths.
//! - [`model`]: a scene resolved into the numbers a backend steps.
//! - [`math`], [`kernel`], [`neighbors`], [`periodic`]: numeric types, SPH kernels, the
//!   uniform grid, periodic domains (minimum-image pairs).
//! - [`eos`], [`viscosity`], [`boundary`], [`sampling`]: the physics pieces of
//!   the fluid module (each names its paper and equation).
//! - [`timestep`], [`guard`]: adaptive dt and the stability guard.
//! - [`backend`], [`cpu`]: the backend trait and the rayon CPU backend.
//! - [`simulation`], [`summary`]: a running scene and its run summary.
//! - [`snapshot`]: a scene's full state as bytes, restored bit for bit.
//! - [`channels`]: the per-particle quantities frames and exports carry.
//! - [`validation`]: reference solutions and error measures.

pub mod attrs;
pub mod backend;
pub mod boundary;
pub mod channels;
pub mod clock;
pub mod cpu;
pub mod guard;
pub mod kernel;
pub mod materials;
pub mod math;
pub mod model;
pub mod modules;
pub mod neighbors;
pub mod periodic;
pub mod plan;
pub mod quantize;
pub mod sampling;
pub mod scene;
pub mod schemes;
pub mod simulation;
pub mod snapshot;
pub mod summary;
pub mod timestep;
pub mod validation;

pub use backend::{Backend, Particles, StepReport};
pub use guard::Halted;
pub use simulation::Simulation;
