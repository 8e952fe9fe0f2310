//! The snow cover as a grid set (`snow_cover`) and its channels: the cover as
//! viewers draw it (on the object standing over a cell's centre, else on the
//! ground; shaded by that surface's coverage), the ground's and the objects'
//! snow apart, and the thesis's coverage.

use super::{COVER, NO_OBJECT, SnowfallConsts};
use crate::attrs::Column;
use crate::channels::{ChannelSpec, SetSpec, Source};
use crate::materials::Look;
use crate::model::{Model, ModelBuilder};

/// A channel of the cover's cells.
fn channel(name: &'static str, unit: &'static str, about: &'static str, source: Source) -> ChannelSpec {
    ChannelSpec { name, unit, components: 1, exact: false, set: COVER, module: "snowfall", about, source }
}

/// Declares the cover's set over `grid` and its channels, the one viewers colour
/// by first.
pub fn declare(b: &mut ModelBuilder, grid: floe_proto::GridInfo) {
    b.set(SetSpec {
        look: Some(Look::Snow),
        surface: Some("cover_height"),
        shade: Some("cover_coverage"),
        ..SetSpec::grid(COVER, super::CELLS, grid)
    });
    let derived = |from, values| Source::Derived { from, values };
    b.channel(channel(
        "cover_depth",
        "m",
        "Depth of the snow on top: on the object over the cell's centre, else on the ground.",
        derived(&["object_top", "top_count", "ground_count"], cover_depths),
    ));
    b.channel(channel(
        "cover_height",
        "m",
        "Height of the snow's surface on top: on the object over the cell's centre, else on the ground.",
        derived(&["object_top", "top_count", "snow_bed", "ground_count"], cover_heights),
    ));
    b.channel(channel("snow_depth", "m", "Depth of the snow on the ground.", derived(&["ground_count"], depths)));
    b.channel(channel(
        "snow_height",
        "m",
        "Height of the snow's surface on the ground (the ground's height plus the snow's depth).",
        derived(&["snow_bed", "ground_count"], heights),
    ));
    b.channel(channel("top_depth", "m", "Depth of the snow on objects' tops.", derived(&["top_count"], depths)));
    b.channel(channel(
        "coverage",
        "",
        "The snow thesis's coverage of the ground (eqs. 2.1-2.2): exposure to the sky times cos(inclination).",
        Source::Attr("coverage"),
    ));
    b.channel(channel(
        "cover_coverage",
        "",
        "The coverage of the surface viewers draw the cover on: the object's top over the cell's centre, else the ground.",
        derived(&["object_top", "top_coverage", "coverage"], cover_coverages),
    ));
}

/// Depth (m) from a count of flakes per cell.
fn depths(model: &Model, columns: &[Column]) -> Vec<f32> {
    let per = model.consts::<SnowfallConsts>().depth_per_flake;
    let Column::U32(n) = &columns[0] else { panic!("counts are u32") };
    n.iter().map(|&n| n as f32 * per).collect()
}

/// The snow's surface (m) from the ground's heights and the counts.
fn heights(model: &Model, columns: &[Column]) -> Vec<f32> {
    let per = model.consts::<SnowfallConsts>().depth_per_flake;
    let (Column::F32(bed), Column::U32(n)) = (&columns[0], &columns[1]) else { panic!("heights and counts") };
    bed.iter().zip(n).map(|(&b, &n)| b + n as f32 * per).collect()
}

/// The snow on top of each cell (m): an object's where one stands over it.
fn cover_depths(model: &Model, columns: &[Column]) -> Vec<f32> {
    let per = model.consts::<SnowfallConsts>().depth_per_flake;
    let (Column::F32(object), Column::U32(top), Column::U32(ground)) = (&columns[0], &columns[1], &columns[2]) else {
        panic!("object tops and counts")
    };
    (0..object.len()).map(|k| per * if object[k] > NO_OBJECT { top[k] } else { ground[k] } as f32).collect()
}

/// The coverage of the surface on top of each cell: an object's where one stands over it.
fn cover_coverages(_: &Model, columns: &[Column]) -> Vec<f32> {
    let (Column::F32(object), Column::F32(top), Column::F32(ground)) = (&columns[0], &columns[1], &columns[2]) else {
        panic!("object tops and coverages")
    };
    (0..object.len()).map(|k| if object[k] > NO_OBJECT { top[k] } else { ground[k] }).collect()
}

/// The height of the snow's surface on top of each cell (m).
fn cover_heights(model: &Model, columns: &[Column]) -> Vec<f32> {
    let per = model.consts::<SnowfallConsts>().depth_per_flake;
    let (Column::F32(object), Column::U32(top), Column::F32(bed), Column::U32(ground)) =
        (&columns[0], &columns[1], &columns[2], &columns[3])
    else {
        panic!("object tops, heights and counts")
    };
    (0..object.len())
        .map(|k| if object[k] > NO_OBJECT { object[k] + per * top[k] as f32 } else { bed[k] + per * ground[k] as f32 })
        .collect()
}
