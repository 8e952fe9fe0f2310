//! The physics modules shipped with the engine, each a folder of its own (its scene
//! section, attributes, passes on both backends, channels, presets, validation cases
//! and docs) that knows the core and the scheme interfaces, never another module.
//! They are registered in [`crate::registry`].

pub mod fluid;
pub mod heat;
pub mod snow;
pub mod snowfall;
pub mod solid;
