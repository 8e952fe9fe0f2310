//! Snowfall through the service: a scene of flakes and a snow cover, no SPH
//! particles, streamed as the flakes' set and the cover's grid frames; an emission
//! too heavy for the server's limits refused before anything is allocated.

mod common;

use floe_client::{Client, FrameRequest};
use floe_proto::Values;

#[tokio::test]
async fn snow_streams_as_flakes_and_a_growing_cover() {
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let info = floe.create_preset("snow_roof", &["snowfall.flutter=1"]).await.unwrap();
    let sets: Vec<(&str, bool)> = info.sets.iter().map(|s| (s.name.as_str(), s.grid)).collect();
    assert_eq!(sets, [("particles", false), ("flakes", false), ("snow_cover", true)]);
    // Viewers draw both as snow, the cover at its surface's heights, shaded by its coverage.
    let looks: Vec<(&str, &str, &str)> =
        info.sets.iter().map(|s| (s.look.as_str(), s.surface.as_str(), s.shade.as_str())).collect();
    assert_eq!(looks, [("", "", ""), ("snow", "", ""), ("snow", "cover_height", "cover_coverage")]);
    let flakes = info.sets.iter().find(|s| s.name == "flakes").unwrap().count;
    let mut depths = Vec::new();
    for _ in 0..2 {
        floe.step(info.scene_id, 40).await.unwrap();
        let request =
            FrameRequest { channels: vec!["snow_depth".into()], set: "snow_cover".into(), ..FrameRequest::default() };
        let mut grid = floe.frames(info.scene_id, request).await.unwrap();
        let frame = grid.next().await.unwrap().unwrap();
        assert_eq!(frame.header.mode, floe_proto::Mode::Grid);
        let cells = grid.particles(frame);
        assert_eq!(cells.grid.expect("cells").dims, [64, 1, 16]);
        let depth = cells.channel("snow_depth").and_then(Values::as_scalars).unwrap();
        depths.push(depth.iter().sum::<f32>() / depth.len() as f32);
    }
    assert!(depths[0] > 0.0 && depths[1] > 1.5 * depths[0], "the cover grows: mean depths {depths:?} m");
    // The flakes: every slot of the ring, positions in the area.
    let request = FrameRequest { set: "flakes".into(), ..FrameRequest::default() };
    let mut frames = floe.frames(info.scene_id, request).await.unwrap();
    let frame = frames.next().await.unwrap().unwrap();
    let p = frames.particles(frame);
    assert_eq!(p.positions.len() as u64, flakes);
    // The SPH set is empty and still streams.
    let mut frames = floe.frames(info.scene_id, FrameRequest::default()).await.unwrap();
    let frame = frames.next().await.unwrap().unwrap();
    assert_eq!(frames.particles(frame).positions.len(), 0);
    // A fall too heavy for the server's particle limit is refused, naming the flakes.
    let e = floe.create_preset("snow_roof", &["snowfall.intensity={\"flakes_per_m2_s\":100000}"]).await.unwrap_err();
    assert_ne!(common::code(&e), tonic::Code::Internal, "{e}");
    assert!(e.to_string().contains("flakes"), "{e}");
    server.shutdown().await;
}

/// The release on request: snow falls on the mountain side (20 cm) with no time
/// set; setting `snowfall.release.at` to 0 releases the cover after the next
/// step, its mass reported as the particles'; a bad time is refused by path; a
/// release that does not fit its room halts the scene and leaves the cover.
#[tokio::test]
async fn the_cover_is_released_on_request() {
    let server = common::TestServer::start().await;
    let mut floe = Client::connect(&server.grpc_url()).await.unwrap();
    let o = ["particle_spacing=0.2", "snowfall.height=3.2", "snowfall.depth_per_hour=540"];
    let with = |more: &'static str| [&o[..], &[more]].concat();
    let info = floe.create_preset("snowfall_then_avalanche", &with("snowfall.release.at=null")).await.unwrap();
    floe.step(info.scene_id, 60).await.unwrap();
    let e = floe.set_parameters(info.scene_id, &["snowfall.release.at=-1"]).await.unwrap_err();
    assert_eq!(common::code(&e), tonic::Code::InvalidArgument, "{e}");
    assert!(e.to_string().contains("snowfall.release.at"), "{e}");
    let ground = |stats: &floe_client::SceneStats, name: &str| {
        stats.measures.iter().find(|m| m.name == name).map(|m| m.value).unwrap_or_else(|| panic!("{name}"))
    };
    let before = floe.stats(info.scene_id).await.unwrap();
    assert_eq!(ground(&before, "snowfall.released_mass"), 0.0);
    floe.set_parameters(info.scene_id, &["snowfall.release.at=0"]).await.unwrap();
    floe.step(info.scene_id, 1).await.unwrap();
    let mass = ground(&floe.stats(info.scene_id).await.unwrap(), "snowfall.released_mass");
    let mut frames = floe.frames(info.scene_id, FrameRequest::default()).await.unwrap();
    let frame = frames.next().await.unwrap().unwrap();
    let particles = frames.particles(frame).positions.len();
    assert!(particles > 100 && mass > 0.0, "{particles} particles, {mass} kg");
    floe.step(info.scene_id, 5).await.unwrap();
    let again = ground(&floe.stats(info.scene_id).await.unwrap(), "snowfall.released_mass");
    assert_eq!(again, mass, "released once");

    // Room for 10 particles only: the release halts the scene, naming the setting.
    let small = floe.create_preset("snowfall_then_avalanche", &with("snowfall.release.particles=10")).await.unwrap();
    floe.set_parameters(small.scene_id, &["snowfall.release.at=4"]).await.unwrap();
    let halted = floe.step(small.scene_id, 200).await.unwrap();
    assert!(halted.halt_reason.contains("raise snowfall.release.particles"), "{}", halted.halt_reason);
    let stats = floe.stats(small.scene_id).await.unwrap();
    assert_eq!(ground(&stats, "snowfall.released"), 0.0);
    assert!(ground(&stats, "snowfall.ground_mass") > 0.0, "the cover stays");
    server.shutdown().await;
}
