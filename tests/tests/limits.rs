//! The limits an admin sets on `floe serve` (`--max-scenes`, `--max-particles`) reach the
//! registry, which refuses what is over them with a message naming the limit.

use clap::Parser;
use floe_server::auth::{AuthMode, Caller};
use floe_server::cli::{Cli, Command};
use floe_server::service::{Registry, SceneSource, ServiceError};
use std::sync::Arc;

async fn create(registry: &Registry, spacing: &str) -> Result<u64, ServiceError> {
    let overrides = vec![format!("particle_spacing={spacing}")];
    let preset = SceneSource::Preset("dam_break".into());
    registry.create(&Caller::local(), preset, overrides).await.map(|h| h.shared.id)
}

#[tokio::test]
async fn serve_limits_refuse_scenes_over_them() {
    let cli = Cli::try_parse_from(["floe", "serve", "--max-scenes", "2", "--max-particles", "5000"]).unwrap();
    let Command::Serve(args) = cli.command else { panic!("not a serve command") };
    let registry = Registry::new(args.options(AuthMode::SingleUser), Arc::new(floe_engine::simulation::cpu_backend));

    // The dam break's 0.5 x 1 x 0.25 m column: 20 x 40 x 10 = 8,000 particles at 2.5 cm.
    let err = create(&registry, "0.025").await.unwrap_err();
    assert!(matches!(err, ServiceError::InvalidArgument(_)), "{err:?}");
    assert_eq!(
        err.to_string(),
        "particle_spacing: the scene has 8000 particles, more than this server's limit of 5000"
    );

    let first = create(&registry, "0.05").await.unwrap();
    create(&registry, "0.05").await.unwrap();
    let err = create(&registry, "0.05").await.unwrap_err();
    assert!(matches!(err, ServiceError::ResourceExhausted(_)), "{err:?}");
    assert_eq!(err.to_string(), "the server holds its limit of 2 scenes; delete one first");
    registry.delete(&Caller::local(), first).await.unwrap();
    create(&registry, "0.05").await.expect("room again after a delete");
    registry.shutdown().await;
}

#[test]
fn limits_must_be_positive() {
    let err = Cli::try_parse_from(["floe", "serve", "--max-scenes", "0"]).unwrap_err();
    assert!(err.to_string().contains("invalid value '0' for '--max-scenes <MAX_SCENES>'"), "{err}");
}
