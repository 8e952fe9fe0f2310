#!/usr/bin/env bash
# Validates the Kubernetes manifests in deploy/kubernetes offline, against the
# Kubernetes API's JSON schemas that the PyPI package kubernetes-validate ships
# (strict: a misspelt or misplaced field fails, as `kubectl apply` would reject it).
#
#   scripts/validate-k8s.sh            # every manifest in deploy/kubernetes
#   scripts/validate-k8s.sh DIR        # the same checks on another kustomize directory
#   scripts/validate-k8s.sh FILE...    # these files only
#
# Checked:
# - every YAML file in deploy/kubernetes but kustomization.yaml (the example Secret
#   included): each document against the schema of its apiVersion and kind in
#   Kubernetes $K8S_VERSION. A kind with no schema fails too: these manifests use
#   only built-in kinds, so a missing schema means a misspelt kind or apiVersion
#   (the validator's own command line would only warn);
# - kustomization.yaml lists only files that exist, and every manifest but the
#   *.example.yaml ones (a file it does not list is never applied);
# - with kubectl installed, the kustomization renders (`kubectl kustomize`, offline)
#   and what it renders validates as well (namespace and image applied).
#
# The validator is installed once into a virtualenv, ${FLOE_VENV_DIR:-target/k8s-venv}
# (that needs PyPI); validating needs no network. Exits non-zero on any failure.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv=${FLOE_VENV_DIR:-$root/target/k8s-venv}
# Absolute, as the script may change directory below.
case $venv in /*) ;; *) venv=$PWD/$venv ;; esac
# The validator and the Kubernetes version it checks against are fixed, so a result
# does not change under us: 1.37.0 ships the schemas of Kubernetes 1.25 to 1.37.
VALIDATOR_VERSION=1.37.0
K8S_VERSION=1.30.0

installed() {
  "$venv/bin/python" -c 'import importlib.metadata as m; print(m.version("kubernetes-validate"))' 2>/dev/null
}
if [ "$(installed || true)" != "$VALIDATOR_VERSION" ]; then
  echo "installing kubernetes-validate $VALIDATOR_VERSION into $venv" >&2
  [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "kubernetes-validate==$VALIDATOR_VERSION"
fi

# Validates the YAML files named (- for stdin) and prints a line per document. The
# program goes in as an argument: stdin may be the data.
validate_py=$(
  cat <<'PY'
import sys
import yaml
import kubernetes_validate as kv

version, paths = sys.argv[1], sys.argv[2:]
failed = False


def fail(where, message):
    global failed
    failed = True
    print(f"FAIL {where}: {message}")


for path in paths:
    try:
        text = sys.stdin.read() if path == "-" else open(path).read()
        path = "<stdin>" if path == "-" else path
        docs = [d for d in yaml.safe_load_all(text) if d is not None]
    except (OSError, yaml.YAMLError) as e:
        fail(path, f"cannot read: {e}")
        continue
    if not docs:
        fail(path, "no Kubernetes object in it")
    for doc in docs:
        if not isinstance(doc, dict) or "apiVersion" not in doc or "kind" not in doc:
            fail(path, "a document without apiVersion and kind")
            continue
        name = f"{doc['kind']}/{(doc.get('metadata') or {}).get('name', '?')}"
        try:
            kv.validate(doc, version, strict=True)
            print(f"ok   {path}: {name}")
        except kv.ValidationError as e:
            field = ".".join(str(p) for p in e.path) or "(top level)"
            fail(f"{path}: {name}", f"{field}: {e.message}")
        except kv.SchemaNotFoundError:
            fail(f"{path}: {name}", f"no schema for kind {doc['kind']} of {doc['apiVersion']} in Kubernetes {version}")
sys.exit(1 if failed else 0)
PY
)
validate() {
  "$venv/bin/python" -c "$validate_py" "$K8S_VERSION" "$@"
}

if [ $# -gt 1 ] || { [ $# = 1 ] && [ ! -d "$1" ]; }; then
  validate "$@"
  exit
fi

if [ $# = 1 ]; then
  manifests=$1
else
  # Paths in the report relative to the checkout.
  cd "$root"
  manifests=deploy/kubernetes
fi
status=0
files=()
for f in "$manifests"/*.yaml "$manifests"/*.yml; do
  [ -e "$f" ] || continue
  [ "$(basename "$f")" = kustomization.yaml ] && continue
  files+=("$f")
done
validate "${files[@]}" || status=1

# kustomization.yaml against the directory: what it lists exists, and what exists
# is listed (example files aside).
"$venv/bin/python" - "$manifests" <<'PY' || status=1
import os, sys
import yaml

d = sys.argv[1]
k = yaml.safe_load(open(os.path.join(d, "kustomization.yaml")))
listed = k.get("resources") or []
failed = False
for r in listed:
    if "://" in r or r.startswith("github.com/"):
        continue
    if not os.path.exists(os.path.join(d, r)):
        print(f"FAIL kustomization.yaml lists {r}, which does not exist")
        failed = True
for f in sorted(os.listdir(d)):
    if f.endswith((".yaml", ".yml")) and f != "kustomization.yaml" and ".example." not in f and f not in listed:
        print(f"FAIL {f} is not in kustomization.yaml's resources (never applied); name it *.example.yaml if on purpose")
        failed = True
if not failed:
    print(f"ok   kustomization.yaml: {len(listed)} resources, all present")
sys.exit(1 if failed else 0)
PY

if command -v kubectl >/dev/null; then
  if rendered=$(kubectl kustomize "$manifests"); then
    echo "kubectl kustomize $manifests renders; what it renders:"
    validate - <<<"$rendered" || status=1
  else
    echo "FAIL kubectl kustomize $manifests"
    status=1
  fi
else
  echo "skip kubectl kustomize: no kubectl"
fi

if [ "$status" = 0 ]; then echo "all manifests valid (Kubernetes $K8S_VERSION, kubernetes-validate $VALIDATOR_VERSION)"; fi
exit "$status"
