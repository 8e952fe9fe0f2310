#!/usr/bin/env bash
# The cluster through its proxy: deploy/local/cluster.sh starts PostgreSQL, nginx and
# three workers on loopback (a 3 s lease, the CPU backend), then the Rust client's test
# (server/tests/cluster_proxy.rs), the Python client's (client/python/tests/
# test_cluster.py) and the viewer's in headless Chromium (tests/browser/
# cluster.test.mjs, and cluster_failover.test.mjs across a worker's death) run
# against the proxy's addresses. Needs target/debug/floe, the
# Python client's virtualenv and tests/browser's packages (tests/run-all.sh makes
# all three first).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(mktemp -d)
trap 'deploy/local/cluster.sh stop "$dir" >/dev/null 2>&1 || true; rm -rf "$dir"' EXIT
eval "$(FLOE_BIN=target/debug/floe FLOE_LEASE=3 FLOE_BACKEND=cpu FLOE_CHECKPOINT_EVERY=1 \
  deploy/local/cluster.sh start "$dir" 3)"
export FLOE_REQUIRE_CLUSTER=1
target/python-venv/bin/python -m pytest -q client/python/tests/test_cluster.py
node --test tests/browser/cluster.test.mjs
# These two kill -9 a worker each: floe-2, then floe-3.
cargo test -q -p floe-server --test cluster_proxy
node --test tests/browser/cluster_failover.test.mjs
