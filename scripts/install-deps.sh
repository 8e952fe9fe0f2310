#!/usr/bin/env bash
# System packages the tests need, installed only when missing: Chromium (the
# viewer test; Debian's build, no browser download), Node.js with npm (the
# JavaScript tests), Mesa's Vulkan drivers (lavapipe, a software GPU the GPU
# backend's tests run on), Python 3 with its venv module (the Python client's
# tests run in a virtualenv; Debian ships venv apart from python3) and PostgreSQL
# (the lab server's tests on PostgreSQL run a throwaway cluster,
# scripts/pg-test-cluster.sh), and nginx (the cluster test's proxy,
# deploy/local/cluster.sh). The Rust build needs none: protoc comes vendored,
# SQLite is compiled in.
set -euo pipefail
need=()
command -v chromium >/dev/null || need+=(chromium)
command -v node >/dev/null || need+=(nodejs)
command -v npm >/dev/null || need+=(npm)
ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1 || need+=(mesa-vulkan-drivers)
command -v python3 >/dev/null || need+=(python3)
python3 -c 'import ensurepip, venv' >/dev/null 2>&1 || need+=(python3-venv)
ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 || need+=(postgresql)
# Debian puts nginx in /usr/sbin, off a non-root user's PATH.
[ -x /usr/sbin/nginx ] || command -v nginx >/dev/null || need+=(nginx)
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null; then
    echo "missing: ${need[*]}; install them (Debian: apt-get install ${need[*]})" >&2
    exit 1
  fi
  echo "installing ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
