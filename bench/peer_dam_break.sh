#!/usr/bin/env bash
# Time to solution on the dam break, Floe against SPlisHSPlasH 2.19 (WCSPH, Akinci
# boundary particles), same geometry, same machine, one run. Prints one table.
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
    awk -F'|' -v l="$label" '{gsub(/ /,""); printf "%s|%s|%s|%s|%s|%s\n", l, $2, $4, $6, $8, $11}'
}
{
  row "Floe WCSPH, c = 10 v_max (default)"
  # SPlisHSPlasH's WCSPH stiffness 50000 Pa with gamma 7 is c = sqrt(50000*7/1000) = 18.7 m/s.
  row "Floe WCSPH, c = 18.7 m/s (peer's stiffness)" --set solver.speed_of_sound=18.7
  LD_PRELOAD=/lib/x86_64-linux-gnu/libGLdispatch.so.0 "$VENV/bin/python" "$PEERS/splishsplash_dam_break.py" \
    --n "$N" --method 0 --stop "$SECONDS_SIM" --out "$tmp/peer.json" > "$tmp/peer.log" 2>&1
  python3 - "$tmp/peer.json" server/engine/data/dam_break_surge_front.csv <<'PY'
import json, sys
peer = json.load(open(sys.argv[1]))
ref = [(float(t), float(z)) for s, t, z in (l.strip().split(",") for l in open(sys.argv[2])
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
print(f"SPlisHSPlasH 2.19 WCSPH (dt 0.5 ms)|{peer['n_fluid']}|{peer['steps']}|{peer['run_wall_s']:.2f}|{rms:.3f}|{z2:.3f}")
PY
} > "$tmp/rows"
echo "dam break, a = 0.5 m, $SECONDS_SIM s simulated, $(nproc) cores; front error against Koshizuka & Oka (T <= 3), reference Z(T=2) = 2.24"
echo "| run | fluid particles | steps | wall s | front RMS | Z(T=2) | wall / peer |"
echo "|---|---:|---:|---:|---:|---:|---:|"
peer_wall=$(tail -1 "$tmp/rows" | cut -d'|' -f4)
while IFS='|' read -r label n steps wall rms z2; do
  printf "| %s | %s | %s | %s | %s | %s | %.2f |\n" "$label" "$n" "$steps" "$wall" "$rms" "$z2" "$(awk -v a="$wall" -v b="$peer_wall" 'BEGIN{print a/b}')"
done < "$tmp/rows"
