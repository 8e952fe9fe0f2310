//! The GPU the tests share, or the reason they are skipped.

use floe_gpu::{Adapters, GpuContext};
use std::sync::OnceLock;

/// A device on any Vulkan adapter (Mesa's lavapipe in CI), opened once per
/// test binary. `None` (after saying why) where there is none, so `cargo test`
/// passes on machines without a Vulkan driver; with `FLOE_REQUIRE_GPU=1` (set
/// by tests/run-all.sh, which installs lavapipe) a missing GPU fails instead.
pub fn gpu(test: &str) -> Option<&'static GpuContext> {
    static GPU: OnceLock<Result<GpuContext, String>> = OnceLock::new();
    match GPU.get_or_init(|| GpuContext::new(Adapters::Any, false).map_err(|e| e.to_string())) {
        Ok(g) => Some(g),
        Err(e) if std::env::var_os("FLOE_REQUIRE_GPU").is_some() => panic!("{test}: FLOE_REQUIRE_GPU is set: {e}"),
        Err(e) => {
            eprintln!("SKIPPED {test}: no GPU ({e})");
            None
        }
    }
}
