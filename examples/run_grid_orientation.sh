#!/usr/bin/env bash
# Crack-path angle versus grid orientation (thesis 5.1.1) for the bond-based deck
# examples/grid_orientation_pmb.yaml, grids rotated by 0, 5, 10, 20, 30, 40 deg, at the printed
# load (0.8 MPa, 560 us) unless LOAD_PA / END_TIME_S say otherwise.
# Usage: examples/run_grid_orientation.sh [LOAD_PA] [END_TIME_S] [OUT] [DECK]
#   DECK = examples/grid_orientation_lps.yaml sweeps the state-based case (printed load 0.7 MPa,
#   400 us).
set -euo pipefail
cd "$(dirname "$0")/.."
deck="${4:-examples/grid_orientation_pmb.yaml}"
printed=$(grep -m1 -o 'value: \[0.0, [0-9.e]*\]' "$deck" | sed -E 's/.*, ([0-9.e]+)\]/\1/')
load="${1:-$printed}"; out="${3:-out/grid_orientation}"
end="${2:-$(grep -m1 'end_time:' "$deck" | awk '{ print $2 }')}"
mkdir -p "$out"
echo "| grid angle (deg) | crack path angle (deg) | initiation (us) |"
echo "|---|---|---|"
for a in 0 5 10 20 30 40; do
  sed -e "s/value: \[0.0, $printed\]/value: [0.0, $load]/" -e "s/value: \[0.0, -$printed\]/value: [0.0, -$load]/" \
      -e "s/rotation_deg: 0.0/rotation_deg: $a/" -e "s/end_time: [0-9.]*e-6/end_time: $end/" \
      "$deck" > "$out/deck_$a.yaml"
  ./build/periadapt run "$out/deck_$a.yaml" --out "$out/angle_$a" --quiet > /dev/null
  s="$out/angle_$a/summary.json"
  ang=$(grep -m1 '"path_angle_deg"' "$s" | sed -E 's/.*: *([-0-9.eE+]+).*/\1/' || true)
  ti=$(grep -m1 '"initiation_time_s"' "$s" | sed -E 's/.*: *//; s/,$//')
  echo "| $a | ${ang:--} | $(awk -v t="$ti" 'BEGIN { if (t == "null") print "-"; else printf "%.1f", t * 1e6 }') |"
done
