#!/usr/bin/env bash
# The Python client's tests, as tests/run-all.sh runs them: a virtualenv under target/,
# the package installed into it with its test extras (the extension built with the dev
# profile, sharing the workspace's build), ruff's lint and format check, then pytest
# against target/debug/floe and target/debug/floectl (`cargo build -p floe-server -p floe-client`)
# and target/debug/examples/floe_traced (`cargo build -p floe-tests --example floe_traced`).
set -euo pipefail
cd "$(dirname "$0")/../../.."
venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q "./client/python[test]" --config-settings=build-args="--profile dev"
(cd client/python && "../../$venv/bin/ruff" check --quiet . && "../../$venv/bin/ruff" format --check --quiet .)
# lavapipe is installed (scripts/install-deps.sh): the GPU round trip must run, not skip.
FLOE_REQUIRE_GPU=1 "$venv/bin/python" -m pytest -q client/python/tests "$@"
