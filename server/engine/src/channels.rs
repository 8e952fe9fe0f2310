//! The per-particle quantities a scene can send in frames and write in exports:
//! each declared once by the module that owns it, with its unit. Names are those of
//! `proto/channels.json` (the wire table) where it has a row; a channel without a row
//! travels under a per-scene tag the server assigns and lists in the scene's info.

/// A channel a module offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChannelSpec {
    /// Name (`velocity`), as clients ask for it.
    pub name: &'static str,
    /// SI unit (`m/s`); empty for an index.
    pub unit: &'static str,
    /// Values per particle.
    pub components: u8,
    /// Sent exactly as raw u8 values (material indices) rather than quantised floats.
    pub exact: bool,
    /// The particle set it belongs to.
    pub set: &'static str,
    /// The module that declares it.
    pub module: &'static str,
    /// What it holds.
    pub about: &'static str,
}

/// The set every SPH scene has: its fluid (and later solid) particles.
pub const PARTICLES: &str = "particles";

/// Velocity (core: every particle set that moves has one).
pub const VELOCITY: ChannelSpec = ChannelSpec {
    name: "velocity",
    unit: "m/s",
    components: 3,
    exact: false,
    set: PARTICLES,
    module: "core",
    about: "Particle velocity.",
};

/// Density (the fluid module's).
pub const DENSITY: ChannelSpec = ChannelSpec {
    name: "density",
    unit: "kg/m^3",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "fluid",
    about: "SPH density.",
};

/// Pressure (the fluid module's), from density through the material's equation of state.
pub const PRESSURE: ChannelSpec = ChannelSpec {
    name: "pressure",
    unit: "Pa",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "fluid",
    about: "Pressure from the equation of state.",
};
