#!/usr/bin/env bash
# Time to solution on the dam break, Floe (WCSPH and DFSPH) against SPlisHSPlasH 2.19
# (WCSPH and DFSPH, Akinci boundary particles), same geometry, same machine, one run.
# Prints one table: wall time, steps, mean solver iterations per step, front RMS and
# the wall time over the fastest peer's.
#
#   bash bench/peer_dam_break.sh            # 21,952 fluid particles, 0.5 s simulated
#
# Needs the peer script from the shared peers folder (PEERS, default ../shared/peers)
# and installs pysplishsplash into .venv-peers on first use.
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=${PEERS:-../shared/peers}
VENV=${VENV:-.venv-peers}
N=${N:-28}
SECONDS_SIM=${SECONDS_SIM:-0.5}
if [ ! -x "$VENV/bin/python" ]; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install -q pysplishsplash==2.19.0 numpy
fi
cargo build -q --release -p floe-server
tmp=$(mktemp -d)
particles=$((N * N * N))

row() { # label, extra floe args...
  local label=$1; shift
  ./target/release/floe bench --particles "$particles" --solve "$SECONDS_SIM" "$@" | tail -1 |
    awk -F'|' -v l="$label" '{gsub(/ /,""); printf "%s|%s|%s|%s|%s|%s|%s|floe\n", l, $2, $4, $6, $8, $11, $12}'
}
peer() { # label, SPlisHSPlasH method (0 WCSPH, 4 DFSPH)
  LD_PRELOAD=/lib/x86_64-linux-gnu/libGLdispatch.so.0 "$VENV/bin/python" "$PEERS/splishsplash_dam_break.py" \
    --n "$N" --method "$2" --stop "$SECONDS_SIM" --out "$tmp/peer$2.json" > "$tmp/peer$2.log" 2>&1
  python3 - "$1" "$tmp/peer$2.json" server/engine/data/dam_break_surge_front.csv <<'PY'
import json, sys
peer = json.load(open(sys.argv[2]))
ref = [(float(t), float(z)) for s, t, z in (l.strip().split(",") for l in open(sys.argv[3])
       if not l.startswith("#") and l.startswith("koshizuka"))]
hist = [(f["T"], f["Z_max"]) for f in peer["front"]]
diffs = []
for t, z in ref:
    if t > 3.0:
        continue
    for (t0, z0), (t1, z1) in zip(hist, hist[1:]):
        if t0 <= t <= t1:
            s = (t - t0) / (t1 - t0) if t1 > t0 else 0.0
            diffs.append(z0 + s * (z1 - z0) - z)
            break
rms = (sum(d * d for d in diffs) / len(diffs)) ** 0.5
z2 = next(z for t, z in hist if t >= 2.0)
iters = peer.get("mean_iterations", "-")
iters = f"{iters:.1f}" if isinstance(iters, (int, float)) else iters
print(f"{sys.argv[1]}|{peer['n_fluid']}|{peer['steps']}|{peer['run_wall_s']:.2f}|{rms:.3f}|{z2:.3f}|{iters}|peer")
PY
}
{
  row "Floe DFSPH, tolerance 0.1 % (the preset's)"
  row "Floe DFSPH, tolerance 0.01 % (the peer's)" --set solver.dfsph.density_tolerance=1e-4
  row "Floe WCSPH, c = 10 v_max" --set 'solver.method="wcsph"'
  # SPlisHSPlasH's WCSPH stiffness 50000 Pa with gamma 7 is c = sqrt(50000*7/1000) = 18.7 m/s.
  row "Floe WCSPH, c = 18.7 m/s (peer's stiffness)" --set 'solver.method="wcsph"' --set solver.speed_of_sound=18.7
  peer "SPlisHSPlasH 2.19 WCSPH (dt 0.5 ms)" 0
  peer "SPlisHSPlasH 2.19 DFSPH (tolerance 0.01 %)" 4
} > "$tmp/rows"
echo "dam break, a = 0.5 m, $SECONDS_SIM s simulated, $(nproc) cores; front error against Koshizuka & Oka (T <= 3), reference Z(T=2) = 2.24"
echo "| run | fluid particles | steps | wall s | iterations/step | front RMS | Z(T=2) | wall / fastest peer |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
fastest=$(awk -F'|' '$8 == "peer" {print $4}' "$tmp/rows" | sort -g | head -1)
while IFS='|' read -r label n steps wall rms z2 iters _; do
  printf "| %s | %s | %s | %s | %s | %s | %s | %.2f |\n" "$label" "$n" "$steps" "$wall" "$iters" "$rms" "$z2" \
    "$(awk -v a="$wall" -v b="$fastest" 'BEGIN{print a/b}')"
done < "$tmp/rows"
