//! The generic map passes on the GPU (floe-engine `maps`): gather, spread,
//! segment sum and member sum, one thread per element of the space written, each
//! sum in membership order so the GPU adds as the CPU does, with no atomics.
//! Entry points `w1`, `w4` and `w12` move 1, 4 or 12 words per element (f32 and
//! u32; vec3, vec4 and quaternions; 3x3 matrices). A module declares its use with
//! [`map_pass!`](crate::map_pass), naming the map, its spaces and attributes as
//! literals; the map's counts come from a uniform named after the map.

/// Joins `common.wgsl` and `map.wgsl` with a map kernel.
macro_rules! map_kernel {
    ($file:literal) => {
        concat!(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/passes/common.wgsl")),
            "\n",
            include_str!("map.wgsl"),
            "\n",
            include_str!($file)
        )
    };
}

/// Source of [`crate::map_pass!`]`(gather ...)`.
pub const GATHER: &str = map_kernel!("gather.wgsl");
/// Source of [`crate::map_pass!`]`(spread ...)`.
pub const SPREAD: &str = map_kernel!("spread.wgsl");
/// Source of [`crate::map_pass!`]`(segment_sum ...)`.
pub const SEGMENT_SUM: &str = map_kernel!("segment_sum.wgsl");
/// Source of [`crate::map_pass!`]`(member_sum ...)`.
pub const MEMBER_SUM: &str = map_kernel!("member_sum.wgsl");

/// A [`crate::pass::GpuPass`] doing one of the generic map passes under a
/// module's pass name, `words` 32-bit words per element on the GPU (1, 4 or 12):
///
/// ```text
/// map_pass!(gather "solid.rest", map "clusters", words 4, from "x" into "clusters_x")
/// map_pass!(spread "solid.goal_frame", map "clusters", words 12, from "cluster_r" into "clusters_r")
/// map_pass!(segment_sum "solid.moment", map "clusters", segments "clusters", words 12, from "clusters_apq" into "cluster_apq")
/// map_pass!(member_sum "solid.goals", map "clusters", members "particles", words 4, from "clusters_goal" into "goal_sum")
/// ```
#[macro_export]
macro_rules! map_pass {
    (gather $pass:literal, map $map:literal, words $w:literal, from $from:literal into $into:literal) => {
        $crate::pass::GpuPass {
            name: $pass,
            source: $crate::maps::GATHER,
            entry: concat!("w", $w),
            bindings: &[
                ($crate::program::Access::Uniform, "params"),
                ($crate::program::Access::Uniform, $map),
                ($crate::program::Access::Read, concat!($map, "_member")),
                ($crate::program::Access::Read, "slot_of"),
                ($crate::program::Access::Read, $from),
                ($crate::program::Access::ReadWrite, $into),
            ],
            space: $map,
            when: $crate::pass::always,
        }
    };
    (spread $pass:literal, map $map:literal, words $w:literal, from $from:literal into $into:literal) => {
        $crate::pass::GpuPass {
            name: $pass,
            source: $crate::maps::SPREAD,
            entry: concat!("w", $w),
            bindings: &[
                ($crate::program::Access::Uniform, "params"),
                ($crate::program::Access::Uniform, $map),
                ($crate::program::Access::Read, concat!($map, "_segment")),
                ($crate::program::Access::Read, $from),
                ($crate::program::Access::ReadWrite, $into),
            ],
            space: $map,
            when: $crate::pass::always,
        }
    };
    (segment_sum $pass:literal, map $map:literal, segments $space:literal, words $w:literal, from $from:literal into $into:literal) => {
        $crate::pass::GpuPass {
            name: $pass,
            source: $crate::maps::SEGMENT_SUM,
            entry: concat!("w", $w),
            bindings: &[
                ($crate::program::Access::Uniform, "params"),
                ($crate::program::Access::Uniform, $map),
                ($crate::program::Access::Read, concat!($map, "_start")),
                ($crate::program::Access::Read, concat!($map, "_len")),
                ($crate::program::Access::Read, concat!($map, "_live")),
                ($crate::program::Access::Read, $from),
                ($crate::program::Access::ReadWrite, $into),
            ],
            space: $space,
            when: $crate::pass::always,
        }
    };
    (member_sum $pass:literal, map $map:literal, members $space:literal, words $w:literal, from $from:literal into $into:literal) => {
        $crate::pass::GpuPass {
            name: $pass,
            source: $crate::maps::MEMBER_SUM,
            entry: concat!("w", $w),
            bindings: &[
                ($crate::program::Access::Uniform, "params"),
                ($crate::program::Access::Uniform, $map),
                ($crate::program::Access::Read, concat!($map, "_first")),
                ($crate::program::Access::Read, concat!($map, "_count")),
                ($crate::program::Access::Read, concat!($map, "_order")),
                ($crate::program::Access::Read, concat!($map, "_live")),
                ($crate::program::Access::Read, "id"),
                ($crate::program::Access::Read, $from),
                ($crate::program::Access::ReadWrite, $into),
            ],
            space: $space,
            when: $crate::pass::always,
        }
    };
}
