#!/usr/bin/env bash
# Every preset at its full size on the CPU backend, one whole process each
# (`floe run P --until T --backend cpu --summary`): particles, pressure scheme, mean time
# step and real-time factor (simulated seconds over wall seconds), as one Markdown table.
# One run each, so the real-time factors are this machine's at that moment (quote ratios
# measured in one paired session, not these, for before/after claims).
#
#   bash bench/presets.sh                  # 0.5 s simulated each (see UNTIL below)
#   FLOE=path/to/floe bash bench/presets.sh
#
# `particles` counts the scene's particles (a snowfall's flakes are not: they are a set
# of their own). The slowest presets run shorter windows and the snow presets longer ones (the
# snowfall's first flakes land after 2 s; snowfall_then_avalanche releases its cover
# at 20 s): the table's `simulated s` column says which.
set -euo pipefail
cd "$(dirname "$0")/.."
FLOE=${FLOE:-}
if [ -z "$FLOE" ]; then
  cargo build -q --release -p floe-server
  FLOE=./target/release/floe
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

until_for() {
  case $1 in
    convection | two_fluids | layers) echo 0.1 ;;
    snowfall | snow_roof) echo 2 ;;
    snowfall_then_avalanche) echo 21 ;;
    bunny | ice_melting | avalanche) echo 2 ;;
    *) echo 0.5 ;;
  esac
}

echo "| preset | particles | scheme | simulated s | steps | mean dt s | wall s | real-time factor | halted |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---|"
for preset in $("$FLOE" presets | awk '{print $1}'); do
  until=$(until_for "$preset")
  # The plan's first line names the scheme ("scene P: scheme dfsph, modules ...").
  scheme=$("$FLOE" plan "$preset" | head -1 | sed -n 's/.*scheme \([a-z]*\),.*/\1/p')
  "$FLOE" run "$preset" --backend cpu --until "$until" --quiet --summary "$tmp/$preset.json" >/dev/null 2>&1 || true
  python3 - "$preset" "$tmp/$preset.json" "$scheme" <<'PY'
import json, sys
preset, path, scheme = sys.argv[1], sys.argv[2], sys.argv[3].upper()
try:
    s = json.load(open(path))
except (OSError, ValueError):
    print(f"| `{preset}` | - | - | - | - | - | - | - | did not run |")
    sys.exit()
rtf = s["simulated_seconds"] / s["wall_seconds"]
halted = s.get("halted") or ""
if isinstance(halted, dict):
    halted = f"at {halted.get('time', 0):.3g} s: {halted.get('reason', '')}"
print(
    f"| `{preset}` | {s['particles']:,} | {scheme} | {s['simulated_seconds']:.3g} | {s['steps']:,} "
    f"| {s['dt_mean']:.3g} | {s['wall_seconds']:.1f} | {rtf:.3g} | {halted} |"
)
PY
done
