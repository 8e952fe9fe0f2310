//! Index maps: many-to-many relations between two index spaces, such as the
//! clusters of a solid and the particles each holds (a particle in several
//! clusters), stored as offsets and members so that sums over a cluster need no
//! float atomics on a GPU.
//!
//! A map relates the elements of a *segment* space (`clusters`) to elements of a
//! *member* space (`particles`); each pair is a *membership*, an element of the
//! map's own space (named after the map), which can hold per-membership data
//! (a particle's rest offset within one cluster). The map is declared once,
//! statically, with [`index_map!`], and built from its segments' member lists by
//! [`crate::model::ModelBuilder::map`]. Its structure is attributes of the
//! three spaces, so snapshots, GPU buffers and pass contracts treat it as any other
//! data:
//!
//! | attribute | space | role | holds |
//! |---|---|---|---|
//! | `{map}_member` | the map's | constant | the member's id (its stable id for particles, which are re-sorted every step) |
//! | `{map}_segment` | the map's | constant | the membership's segment |
//! | `{map}_live` | the map's | state | 1 while the membership holds, 0 once the member left |
//! | `{map}_start`, `{map}_len` | segments | constant | the segment's memberships: `start .. start + len` |
//! | `{map}_order` | the map's | constant | memberships ordered by member id |
//! | `{map}_first`, `{map}_count` | `{map}_by_member` (one per member id) | constant | the member's memberships: `order[first .. first + count]` |
//!
//! A member leaves a segment at run time by its membership's `live` becoming 0
//! (a pass that writes `{map}_live`); the structure never changes, so nothing is
//! reallocated and every sum keeps its order. Restored snapshots bring the `live`
//! flags back with the rest of the state.
//!
//! Four generic passes ([`cpu`], and the same four kernels on the GPU) move values
//! along a map, each in a fixed order so both backends sum alike:
//! - [`cpu::Gather`]: member → membership (`out[k] = values[slot of member[k]]`),
//! - [`cpu::Spread`]: segment → membership (`out[k] = values[segment[k]]`),
//! - [`cpu::SegmentSum`]: memberships → segment, the sum over the segment's live
//!   memberships in membership order (a cluster's mass-weighted centre, its moment
//!   matrix `A_pq`),
//! - [`cpu::MemberSum`]: memberships → member, the sum over the member's live
//!   memberships in membership order (a particle's goal positions over its clusters).
//!
//! A module declares each use as a [`crate::plan::PassSpec`] of its own, reading
//! what the table above says the generic pass reads (the CPU view and the GPU
//! bindings hold it to that).

pub mod cpu;

use crate::attrs::{AttrSpec, Column, PARTICLES};

/// A map's declaration: its spaces and the attributes that hold its structure.
#[derive(Debug)]
pub struct MapSpec {
    /// The map's name, also its space of memberships (and the GPU uniform with its counts).
    pub name: &'static str,
    /// The space of segments (clusters); never the particle space, which is re-sorted.
    pub segments: &'static str,
    /// The space of members (particles, by stable id).
    pub members: &'static str,
    /// The space of member ids (`{map}_by_member`).
    pub by_member: &'static str,
    /// Member id per membership.
    pub member: AttrSpec,
    /// Segment per membership.
    pub segment: AttrSpec,
    /// Whether each membership holds (1) or its member left (0).
    pub live: AttrSpec,
    /// First membership of each segment.
    pub start: AttrSpec,
    /// Memberships of each segment.
    pub len: AttrSpec,
    /// Memberships ordered by member id.
    pub order: AttrSpec,
    /// First entry of `order` of each member id.
    pub first: AttrSpec,
    /// Entries of `order` of each member id.
    pub count: AttrSpec,
}

/// Declares a [`MapSpec`]: `index_map!("clusters_members", segments: "clusters",
/// members: PARTICLES, module: "solid")`, names given as literals.
#[macro_export]
macro_rules! index_map {
    ($name:literal, segments: $segments:expr, members: $members:expr, module: $module:literal) => {{
        use $crate::attrs::{AttrSpec, Elem, Role};
        const fn attr(name: &'static str, space: &'static str, role: Role, about: &'static str) -> AttrSpec {
            AttrSpec { name, elem: Elem::U32, unit: "", role, added_later: false, space, module: $module, about }
        }
        const BY_MEMBER: &str = concat!($name, "_by_member");
        $crate::maps::MapSpec {
            name: $name,
            segments: $segments,
            members: $members,
            by_member: BY_MEMBER,
            member: attr(concat!($name, "_member"), $name, Role::Constant, "Member id of each membership."),
            segment: attr(concat!($name, "_segment"), $name, Role::Constant, "Segment of each membership."),
            live: attr(concat!($name, "_live"), $name, Role::State, "1 while the membership holds, 0 once it left."),
            start: attr(concat!($name, "_start"), $segments, Role::Constant, "First membership of each segment."),
            len: attr(concat!($name, "_len"), $segments, Role::Constant, "Memberships of each segment."),
            order: attr(concat!($name, "_order"), $name, Role::Constant, "Memberships ordered by member id."),
            first: attr(concat!($name, "_first"), BY_MEMBER, Role::Constant, "First entry of the order per member id."),
            count: attr(concat!($name, "_count"), BY_MEMBER, Role::Constant, "Entries of the order per member id."),
        }
    }};
}

/// A map's structure built from member lists, as the columns of its attributes.
#[derive(Debug, Clone, PartialEq)]
pub struct Structure {
    /// Memberships.
    pub memberships: usize,
    /// `(attribute, column)` for each of the map's attributes.
    pub columns: Vec<(&'static AttrSpec, Column)>,
}

impl MapSpec {
    /// Whether members are particles, addressed by stable id (and found by
    /// `slot_of` after each sort).
    pub fn sorted(&self) -> bool {
        self.members == PARTICLES
    }

    /// The structure of segments `lists` (each a list of member ids below
    /// `members`), every membership live. Panics on a member id out of range (a
    /// module's error, not a user's).
    pub fn structure(&'static self, lists: &[Vec<u32>], members: usize) -> Structure {
        assert!(self.segments != PARTICLES, "map {}: segments cannot be the re-sorted particle space", self.name);
        let total: usize = lists.iter().map(Vec::len).sum();
        let mut member = Vec::with_capacity(total);
        let mut segment = Vec::with_capacity(total);
        let (mut start, mut len) = (Vec::with_capacity(lists.len()), Vec::with_capacity(lists.len()));
        for (s, list) in lists.iter().enumerate() {
            start.push(member.len() as u32);
            len.push(list.len() as u32);
            for &m in list {
                assert!((m as usize) < members, "map {}: member {m} of segment {s} out of {members}", self.name);
                member.push(m);
                segment.push(s as u32);
            }
        }
        // Counting sort of the memberships by member id (stable: membership order
        // within a member).
        let mut count = vec![0u32; members];
        for &m in &member {
            count[m as usize] += 1;
        }
        let mut first = Vec::with_capacity(members);
        let mut at = 0u32;
        for &c in &count {
            first.push(at);
            at += c;
        }
        let mut next = first.clone();
        let mut order = vec![0u32; total];
        for (k, &m) in member.iter().enumerate() {
            order[next[m as usize] as usize] = k as u32;
            next[m as usize] += 1;
        }
        let columns = vec![
            (&self.member, Column::U32(member)),
            (&self.segment, Column::U32(segment)),
            (&self.live, Column::U32(vec![1; total])),
            (&self.start, Column::U32(start)),
            (&self.len, Column::U32(len)),
            (&self.order, Column::U32(order)),
            (&self.first, Column::U32(first)),
            (&self.count, Column::U32(count)),
        ];
        Structure { memberships: total, columns }
    }

    /// Every attribute of the map.
    pub fn attrs(&'static self) -> [&'static AttrSpec; 8] {
        [&self.member, &self.segment, &self.live, &self.start, &self.len, &self.order, &self.first, &self.count]
    }
}

/// A map's element counts, for a GPU uniform named after the map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Counts {
    /// Segments.
    pub segments: u32,
    /// Memberships.
    pub memberships: u32,
    /// Members.
    pub members: u32,
    /// 1 when members are particles (addressed by id through `slot_of`), else 0.
    pub sorted: u32,
}

impl Counts {
    /// The counts of `map` in `layout`.
    pub fn of(map: &MapSpec, layout: &crate::model::Layout) -> Self {
        Self {
            segments: layout.count(map.segments) as u32,
            memberships: layout.count(map.name) as u32,
            members: layout.count(map.members) as u32,
            sorted: u32::from(map.sorted()),
        }
    }
}

#[cfg(test)]
mod tests;
