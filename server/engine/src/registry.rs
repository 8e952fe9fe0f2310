//! The one list of what the engine is made of: its schemes and its modules. Adding a
//! module or a scheme is one line here (and its folder); nothing else in the engine,
//! the server, the CLI or the viewer names it. This is the only file of the core that
//! names a scheme or a module (`tests/layers.rs` checks it).

use crate::module::ModuleDef;
use crate::scheme::SchemeDef;
use crate::{modules, schemes};

/// The modules, in the order their passes are declared within a stage (ties only:
/// passes are ordered by what they read and write).
pub static MODULES: &[&ModuleDef] = &[
    &modules::fluid::MODULE,
    &modules::heat::MODULE,
    &modules::snow::MODULE,
    &modules::snowfall::MODULE,
    &modules::solid::MODULE,
];

/// The schemes; the first is a scene's scheme when it names none.
pub static SCHEMES: &[&SchemeDef] = &[&schemes::wcsph::SCHEME, &schemes::dfsph::SCHEME];
