#!/usr/bin/env bash
# What adapt.ghost_correction costs, in alternating runs (the machine is noisy), smallest of
# REPEATS wall times (summary.json's wall_time_s) and their ratios to the plain source-horizon run:
#  - the SENT specimen with its crack band refined before the run (examples/pdro_sent_2d.yaml,
#    as tests/validation_sent_levels.sh): source-horizon pairing, the same with the ghost
#    correction, and the dual-horizon pairing (the other cure for the band's interface error);
#  - an adaptive LPS run with many refinement events (the suite's double-edge-notched plate,
#    automatic profile) with and without the correction (each event updates the table).
#   bash bench/ghost_correction.sh [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
[[ -x build/periadapt ]] || bash scripts/build.sh
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
band='{max_level: 1, initial_refinement: [{region: {box: {min: [0.0, -0.012], max: [0.1, 0.012]}}, level: 1}]}'
band_ghost='{max_level: 1, ghost_correction: true, initial_refinement: [{region: {box: {min: [0.0, -0.012], max: [0.1, 0.012]}}, level: 1}]}'
wall() {  # deck, then --set words -> wall time
  local deck=$1; shift
  build/periadapt run "$deck" --quiet --set "output.directory=$out/run" "$@" > /dev/null
  python3 -c "import json; print(json.load(open('$out/run/summary.json'))['wall_time_s'])"
}
declare -A t
sent=examples/pdro_sent_2d.yaml den=bench/agrs/double_edge_notch_lps.yaml
for ((k = 0; k < repeats; ++k)); do
  t[sent]+=" $(wall $sent --set "adapt=$band")"
  t[sent_ghost]+=" $(wall $sent --set "adapt=$band_ghost")"
  t[sent_dual]+=" $(wall $sent --set "adapt=$band" --set solver.bond_pairing=dual_horizon)"
  t[den]+=" $(wall $den)"
  t[den_ghost]+=" $(wall $den --set adapt.ghost_correction=true)"
done
python3 - "${t[sent]}" "${t[sent_ghost]}" "${t[sent_dual]}" "${t[den]}" "${t[den_ghost]}" <<'PY'
import sys
s, sg, sd, d, dg = (min(float(v) for v in a.split()) for a in sys.argv[1:6])
print(f"SENT band: source horizon {s:.3f} s, + ghost correction {sg:.3f} s ({sg / s:.3f}x), "
      f"dual horizon {sd:.3f} s ({sd / s:.3f}x)")
print(f"DEN plate, automatic profile: plain {d:.3f} s, + ghost correction {dg:.3f} s ({dg / d:.3f}x)")
PY
