//! Terrain scenes through the service: assets read from the server's assets
//! directory only, refused with INVALID_ARGUMENT / 400 naming the field, and the
//! height grid served to the viewer.

use floe_proto::pb::scene_service_client::SceneServiceClient;
use floe_proto::pb::{self, create_scene_request::Source};
use floe_server::service::{Options, Registry};
use std::sync::Arc;
use tonic::Code;

mod common;
use common::{TestServer, http};

/// A fluid block over a terrain whose heights are `heights` (a TOML inline table).
fn scene(heights: &str) -> String {
    format!(
        r#"
        particle_spacing = 0.05
        [[fluids]]
        blocks = [{{ min = [0, 0.5, 0], max = [0.3, 0.8, 0.3] }}]
        [[boundaries]]
        kind = "box"
        min = [0, -0.5, 0]
        max = [1, 1, 0.5]
        open = ["+y"]
        [[boundaries]]
        kind = "terrain"
        min = [0, 0]
        max = [1, 0.5]
        friction = 0.3
        heights = {heights}
        "#
    )
}

fn document(text: String) -> pb::CreateSceneRequest {
    pb::CreateSceneRequest {
        source: Some(Source::Document(text)),
        document_format: "toml".into(),
        overrides: vec![],
        backend: String::new(),
    }
}

/// A 3 x 2 grayscale 8-bit PNG: row 0 black, grey, white; row 1 white.
fn png() -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut e = png::Encoder::new(&mut bytes, 3, 2);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&[0, 51, 255, 255, 255, 255]).unwrap();
    w.finish().unwrap();
    bytes
}

async fn server_with_assets(dir: Option<&std::path::Path>) -> TestServer {
    let options = Options { assets: dir.map(|d| d.to_path_buf()), ..Options::default() };
    TestServer::start_with(Arc::new(Registry::new(options, Arc::new(floe_engine::simulation::cpu_backend)))).await
}

#[tokio::test]
async fn assets_come_only_from_the_assets_directory() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("hill.png"), png()).unwrap();
    let with = server_with_assets(Some(dir.path())).await;
    let without = server_with_assets(None).await;
    let mut c = SceneServiceClient::new(with.channel().await);
    let mut bare = SceneServiceClient::new(without.channel().await);
    let asset = |name: &str| format!("{{ source = \"png\", asset = {name:?}, height_range = [0, 0.5] }}");

    // Paths out of the directory, on either server: refused before anything is read.
    let outside = dir.path().join("hill.png").display().to_string();
    for name in ["../hill.png", "sub/hill.png", "..\\hill.png", outside.as_str()] {
        for client in [&mut c, &mut bare] {
            let e = client.create_scene(document(scene(&asset(name)))).await.unwrap_err();
            assert_eq!(e.code(), Code::InvalidArgument, "{name}: {e:?}");
            assert!(
                e.message().starts_with("boundaries[1].heights.asset: must be a plain file name"),
                "{}",
                e.message()
            );
        }
    }
    // A server without an assets directory refuses every asset; a missing file is refused.
    let e = bare.create_scene(document(scene(&asset("hill.png")))).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(
        e.message().contains("boundaries[1].heights.asset: \"hill.png\": no assets directory was given (--assets DIR)"),
        "{}",
        e.message()
    );
    let e = c.create_scene(document(scene(&asset("nope.png")))).await.unwrap_err();
    assert_eq!(
        (e.code(), e.message()),
        (Code::InvalidArgument, "boundaries[1].heights.asset: no asset named \"nope.png\" in the assets directory")
    );
    // REST: 400 with the same message.
    let body = serde_json::json!({ "document": scene(&asset("../hill.png")) }).to_string();
    let a = http(with.http, "POST", "/api/v1/scenes", &[], &body).await;
    assert_eq!(a.status, 400);
    assert!(a.error().starts_with("boundaries[1].heights.asset: must be a plain file name"), "{}", a.error());

    // A real asset: the scene is built, and its heights are served for the viewer.
    let info = c.create_scene(document(scene(&asset("hill.png")))).await.unwrap().into_inner();
    let a = http(with.http, "GET", &format!("/api/v1/scenes/{}/terrain", info.scene_id), &[], "").await;
    assert_eq!(a.status, 200);
    let t = &a.json()["terrains"][0];
    assert_eq!((t["boundary"].as_u64(), t["nx"].as_u64(), t["nz"].as_u64()), (Some(1), Some(3), Some(2)));
    assert_eq!((t["min"].clone(), t["max"].clone()), (serde_json::json!([0.0, 0.0]), serde_json::json!([1.0, 0.5])));
    let heights: Vec<f64> = t["heights"].as_array().unwrap().iter().map(|h| h.as_f64().unwrap()).collect();
    let want = [0.0, 0.1, 0.5, 0.5, 0.5, 0.5];
    assert!(heights.iter().zip(want).all(|(h, w)| (h - w).abs() < 1e-6), "{heights:?}");
    // A scene without a terrain has none.
    let preset = pb::CreateSceneRequest {
        source: Some(Source::Preset("dam_break".into())),
        document_format: String::new(),
        overrides: vec!["particle_spacing=0.1".into()],
        backend: String::new(),
    };
    let plain = c.create_scene(preset).await.unwrap().into_inner();
    let a = http(with.http, "GET", &format!("/api/v1/scenes/{}/terrain", plain.scene_id), &[], "").await;
    assert_eq!((a.status, a.json()), (200, serde_json::json!({ "terrains": [] })));
    with.shutdown().await;
    without.shutdown().await;
}

#[test]
fn floe_run_reads_assets_from_its_assets_directory_only() {
    use clap::Parser;
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("hill.png"), png()).unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene("{ source = \"png\", asset = \"hill.png\", height_range = [0, 0.5] }")).unwrap();
    let floe = |extra: &[&str]| {
        let mut argv = vec!["floe", "run", path.to_str().unwrap(), "--until", "0.002", "--backend", "cpu", "--quiet"];
        argv.extend_from_slice(extra);
        floe_server::execute(floe_server::cli::Cli::try_parse_from(argv).unwrap())
    };
    let err = floe(&[]).unwrap_err();
    assert!(
        format!("{err:#}")
            .starts_with("boundaries[1].heights.asset: \"hill.png\": no assets directory was given (--assets DIR)"),
        "{err:#}"
    );
    floe(&["--assets", dir.path().to_str().unwrap()]).unwrap();
}
