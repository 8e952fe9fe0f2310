#!/usr/bin/env bash
# All of Floe's tests: Rust (unit, physics, validation, service end to end), the
# JavaScript frame decoder against the golden frames, the viewer in headless
# Chromium, and the Python client against a real server. Installs missing system
# packages first (scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
echo "== Rust tests"
# Mesa's device-select layer wants a runtime directory (absent in CI containers).
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "$XDG_RUNTIME_DIR" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"
  export XDG_RUNTIME_DIR
fi
# scripts/install-deps.sh installed lavapipe: the GPU tests must run, not skip.
FLOE_REQUIRE_GPU=1 cargo test --workspace
echo "== JavaScript decoder against the golden frames"
node --test web/test/
echo "== viewer in headless Chromium"
cargo build -q -p floe-server -p floe-client
(cd tests/browser && npm ci --no-audit --no-fund --silent)
node --test tests/browser/
echo "== Python client (client/python) against floe serve"
bash client/python/scripts/test.sh
