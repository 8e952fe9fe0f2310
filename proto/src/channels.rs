//! The channel table: every channel a frame can carry, defined once in
//! `proto/channels.json` (this table is generated from it at build time) and used
//! by the server, the clients and, through a checked copy, the viewer.
//!
//! A channel is identified on the wire by a one-byte tag. Tags of the table are
//! fixed forever. Tags in [`DYNAMIC_TAGS`] belong to channels a module declares
//! without a row in the table: a server assigns them per scene and lists them in
//! the scene's info with their names and units, and every decoder decodes them
//! like any other channel (the channel table of a frame says how).

/// One row of `channels.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChannelDef {
    /// Name used everywhere (`velocity`): requests, exports, the viewer.
    pub name: &'static str,
    /// Wire tag.
    pub tag: u8,
    /// Components per particle (1 to 4).
    pub components: u8,
    /// SI unit (`m/s`), empty for a dimensionless index.
    pub unit: &'static str,
    /// Sent exactly as raw u8 values rather than quantised floats.
    pub exact: bool,
    /// Default quantisation bits.
    pub bits: u8,
    /// What it holds.
    pub about: &'static str,
}

/// What a channel holds: its wire tag. [`ChannelKind::def`] gives the table's row for
/// tags the table defines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ChannelKind(pub u8);

include!(concat!(env!("OUT_DIR"), "/channels.rs"));

impl ChannelKind {
    /// The numeric tag written in the channel table.
    pub fn tag(self) -> u8 {
        self.0
    }

    /// The table's row for this tag, if the table defines it.
    pub fn def(self) -> Option<&'static ChannelDef> {
        CHANNELS.get(usize::from(self.0))
    }

    /// The kind the table names `name`.
    pub fn named(name: &str) -> Option<ChannelKind> {
        CHANNELS.iter().find(|c| c.name == name).map(|c| ChannelKind(c.tag))
    }

    /// Whether the tag is one a server assigns per scene.
    pub fn is_dynamic(self) -> bool {
        DYNAMIC_TAGS.contains(&self.0)
    }

    /// Whether values travel as raw u8 (per the table; dynamic channels are floats).
    pub fn exact(self) -> bool {
        self.def().is_some_and(|d| d.exact)
    }

    /// The table's name, or `channel <tag>` for a tag it does not define.
    pub fn name(self) -> String {
        self.def().map_or_else(|| format!("channel {}", self.0), |d| d.name.to_string())
    }
}

impl std::fmt::Display for ChannelKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_tag_order_below_the_dynamic_tags() {
        for (i, c) in CHANNELS.iter().enumerate() {
            assert_eq!(usize::from(c.tag), i, "{}", c.name);
            assert!(!DYNAMIC_TAGS.contains(&c.tag));
            assert!((1..=4).contains(&c.components) && (1..=16).contains(&c.bits), "{}", c.name);
            assert_eq!(ChannelKind::named(c.name), Some(ChannelKind(c.tag)));
        }
        assert_eq!(ChannelKind::VELOCITY.def().unwrap().unit, "m/s");
        assert_eq!(ChannelKind(70).name(), "channel 70");
        assert!(ChannelKind(70).is_dynamic() && !ChannelKind::MATERIAL.is_dynamic());
        assert!(ChannelKind::MATERIAL.exact());
    }
}
