#!/usr/bin/env bash
# All of Floe's tests: Rust (unit, physics, validation, service end to end, the lab
# server on SQLite and on a throwaway PostgreSQL cluster), the JavaScript frame
# decoder against the golden frames, the viewer in headless Chromium, the
# Python client against a real server, a cluster of workers behind nginx, and the
# Kubernetes manifests against the API's schemas. Installs missing system packages first
# (scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Every server the tests start keeps each preset's own resolution (`floe serve
# --preset-size full`): they count particles and compare figures. The viewer's test of
# presets sized to the machine asks for `auto` on its command line.
export FLOE_PRESET_SIZE=full
echo "== Rust tests"
# Mesa's device-select layer wants a runtime directory (absent in CI containers).
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "$XDG_RUNTIME_DIR" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"
  export XDG_RUNTIME_DIR
fi
# A PostgreSQL cluster of our own on a free port, stopped however the tests end.
# (Assigned first: a cluster that does not start stops the tests here, naming why.)
pg_env=$(bash scripts/pg-test-cluster.sh start)
eval "$pg_env"
trap 'bash scripts/pg-test-cluster.sh stop "$FLOE_TEST_PG_DIR"' EXIT
# scripts/install-deps.sh installed lavapipe and PostgreSQL: those tests must run, not skip.
FLOE_REQUIRE_GPU=1 FLOE_REQUIRE_POSTGRES=1 cargo test --workspace
echo "== JavaScript decoder against the golden frames"
node --test web/test/
echo "== viewer in headless Chromium"
# floe, floectl, and floe with the tests' tracer module compiled in (its grid).
cargo build -q -p floe-server -p floe-client
cargo build -q -p floe-tests --example floe_traced
(cd tests/browser && npm ci --no-audit --no-fund --silent)
node --test tests/browser/
echo "== Python client (client/python) against floe serve"
bash client/python/scripts/test.sh
echo "== a cluster of three workers behind nginx (tests/cluster.sh)"
bash tests/cluster.sh
echo "== Kubernetes manifests against the API's schemas, offline (scripts/validate-k8s.sh)"
bash scripts/validate-k8s.sh
