//! The per-particle quantities a scene can send in frames and write in exports:
//! each declared once by the module that owns it, with its unit and where its
//! values come from. Names are those of `proto/channels.json` (the wire table)
//! where it has a row; a channel without a row travels under a per-scene tag the
//! server assigns and lists in the scene's info.

use crate::attrs::Column;
use crate::materials::MaterialKind;
use crate::model::Model;

/// Where a channel's values come from.
#[derive(Debug, Clone, Copy)]
pub enum Source {
    /// An attribute's values, as they are.
    Attr(&'static str),
    /// Computed from attributes (in the order given, one element each) and the model,
    /// e.g. pressure from density through each material's equation of state.
    Derived {
        /// The attributes it needs.
        from: &'static [&'static str],
        /// The computation: one value per element, `components` floats each.
        values: fn(&Model, &[Column]) -> Vec<f32>,
    },
}

/// A channel a module offers.
#[derive(Debug, Clone, Copy)]
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
    /// Its values.
    pub source: Source,
}

impl PartialEq for ChannelSpec {
    fn eq(&self, other: &Self) -> bool {
        (self.name, self.unit, self.components, self.exact, self.set, self.module)
            == (other.name, other.unit, other.components, other.exact, other.set, other.module)
    }
}

/// A set of particles a frame can carry: its space and the attributes that place
/// and identify its particles; or a grid, a module's field on regular cells (a
/// snow depth over the ground), whose cells are its space's elements, x fastest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetSpec {
    /// Name, as stream requests give it.
    pub name: &'static str,
    /// The index space of its attributes.
    pub space: &'static str,
    /// The attribute holding positions (a vec3).
    pub position: &'static str,
    /// The attribute holding each slot's stable id, for a space that is re-sorted
    /// (values come out in id order); `None` when slots never move.
    pub id: Option<&'static str>,
    /// The cells, for a grid (its frames are grid frames; `position` is unused).
    pub grid: Option<floe_proto::GridInfo>,
    /// How viewers draw it (`None`: as a module's points or a field's colour map).
    pub look: Option<crate::materials::Look>,
    /// For a grid: the channel holding each cell's surface height (m), where
    /// viewers draw the cell (`None`: at the grid's floor).
    pub surface: Option<&'static str>,
    /// For a grid in a look: the channel (0 to 1) by which viewers scale how much
    /// of the look they draw over each cell (`None`: all of it).
    pub shade: Option<&'static str>,
    /// For a part of the SPH particles: the kind of material of its particles (the
    /// solid's, the fluid's). Its members change as particles change phase (ice
    /// melting into water leaves `solid` for `fluid`), keeping their ids, so its
    /// frames carry ids; it offers the SPH particles' channels. `None`: every
    /// element of its space.
    pub kind: Option<MaterialKind>,
}

impl SetSpec {
    /// A grid set: the cells `grid` of space `space` (one element per cell, x
    /// fastest, then y, then z).
    pub fn grid(name: &'static str, space: &'static str, grid: floe_proto::GridInfo) -> Self {
        Self {
            name,
            space,
            position: "",
            id: None,
            grid: Some(grid),
            look: None,
            surface: None,
            shade: None,
            kind: None,
        }
    }

    /// A set of a module's own particles, positions in `position`, its slots fixed.
    pub const fn points(name: &'static str, space: &'static str, position: &'static str) -> Self {
        Self { name, space, position, id: None, grid: None, look: None, surface: None, shade: None, kind: None }
    }

    /// The SPH particles whose material is of kind `kind`, named as the kind.
    pub const fn part(kind: MaterialKind) -> Self {
        Self { name: kind.name(), kind: Some(kind), ..PARTICLE_SET }
    }

    /// The set whose channels it offers: [`PARTICLES`] for a part of them, else its own.
    pub fn channel_set(&self) -> &'static str {
        if self.kind.is_some() { PARTICLES } else { self.name }
    }
}

/// The set every SPH scene has: its fluid (and later solid) particles.
pub const PARTICLES: &str = "particles";

/// The SPH particle set.
pub const PARTICLE_SET: SetSpec = SetSpec {
    name: PARTICLES,
    space: PARTICLES,
    position: "x",
    id: Some("id"),
    grid: None,
    look: None,
    surface: None,
    shade: None,
    kind: None,
};

/// Velocity (core: every particle set that moves has one).
pub const VELOCITY: ChannelSpec = ChannelSpec {
    name: "velocity",
    unit: "m/s",
    components: 3,
    exact: false,
    set: PARTICLES,
    module: "core",
    about: "Particle velocity.",
    source: Source::Attr("v"),
};

/// SPH density: summed, or integrated where the scheme does (δ-SPH).
pub const DENSITY: ChannelSpec = ChannelSpec {
    name: "density",
    unit: "kg/m^3",
    components: 1,
    exact: false,
    set: PARTICLES,
    module: "core",
    about: "SPH density.",
    source: Source::Attr("rho"),
};

/// Material index (scenes with more than one material).
pub const MATERIAL: ChannelSpec = ChannelSpec {
    name: "material",
    unit: "",
    components: 1,
    exact: true,
    set: PARTICLES,
    module: "core",
    about: "Index of the particle's material in the scene's material table.",
    source: Source::Attr("material"),
};
