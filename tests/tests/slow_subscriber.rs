//! A subscriber that never reads must not slow the solver or grow the server's
//! memory: frames are latest-only, so it simply misses them. (One test in its
//! own binary, so no other test shares the machine while it measures.)

use floe_proto::pb::scene_service_client::SceneServiceClient;
use floe_proto::pb::{self, create_scene_request::Source};
use std::time::Duration;

mod common;

fn rss_bytes() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_subscriber_that_never_reads_does_not_slow_stepping() {
    let server = common::TestServer::start().await;
    let mut client = SceneServiceClient::new(server.channel().await);
    let req = pb::CreateSceneRequest {
        // A column at rest costs the same per step all along, so the two windows compare.
        source: Some(Source::Preset("hydrostatic".into())),
        document_format: String::new(),
        overrides: vec!["particle_spacing=0.025".into()],
        backend: String::new(),
    };
    let id = client.create_scene(req).await.unwrap().into_inner().scene_id;
    client.run(pb::RunRequest { scene_id: id, real_time_factor: 0.0 }).await.unwrap();
    let steps = |c: &mut SceneServiceClient<_>| {
        let mut c = c.clone();
        async move { c.get_scene(pb::SceneRef { scene_id: id }).await.unwrap().into_inner().steps }
    };
    let window = Duration::from_secs(3);
    tokio::time::sleep(Duration::from_millis(500)).await;
    let a = steps(&mut client).await;
    tokio::time::sleep(window).await;
    let alone = steps(&mut client).await - a;

    // A stream opened and never read, at the highest rate and with every channel.
    let mut other = SceneServiceClient::new(server.channel().await);
    let request = pb::StreamFramesRequest {
        scene_id: id,
        channels: vec![pb::Channel::Velocity as i32, pb::Channel::Density as i32, pb::Channel::Pressure as i32],
        max_fps: 240.0,
        position_bits: 16,
        mode: pb::FrameMode::Identity as i32,
        decimation: 1,
        ..Default::default()
    };
    let never_read = other.stream_frames(request).await.unwrap().into_inner();
    // Until the transport's flow-control windows fill (about 1 MiB), frames still
    // flow into buffers; after that the stream is stalled for good.
    tokio::time::sleep(Duration::from_secs(3)).await;
    let rss_before = rss_bytes();
    let b = steps(&mut client).await;
    tokio::time::sleep(window).await;
    let with_stalled = steps(&mut client).await - b;
    let rss_after = rss_bytes();

    let stats = client.get_stats(pb::SceneRef { scene_id: id }).await.unwrap().into_inner();
    // Alone again, so machine drift between the windows cancels out.
    drop(never_read);
    tokio::time::sleep(Duration::from_millis(500)).await;
    let c = steps(&mut client).await;
    tokio::time::sleep(window).await;
    let alone = (alone + steps(&mut client).await - c) / 2;
    eprintln!(
        "steps in {window:?}: alone {alone} (mean of before and after), with a stalled subscriber {with_stalled}; dropped {}",
        stats.dropped_frames
    );
    // A solver that waited on this subscriber would stop (0 steps). Run-to-run noise on a
    // shared 2-core machine is about +-20 %, so the bound here is 0.7, not the 0.9 a quiet
    // machine would allow.
    assert!(with_stalled as f64 >= 0.7 * alone as f64, "stepping slowed: {alone} -> {with_stalled} steps");
    assert!(stats.dropped_frames > 0, "the stalled subscriber should be skipping frames");
    let grown = rss_after.saturating_sub(rss_before);
    assert!(grown < 16 << 20, "server memory grew by {grown} bytes while a subscriber stalled");
    server.shutdown().await;
}
