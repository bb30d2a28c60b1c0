#!/usr/bin/env bash
# What a surface correction costs an adaptive run, in alternating runs (the machine is noisy):
# a deck (default: the suite's notched beam in three-point bending, PMB, about 50-100 refinement
# events) with `surface_correction: energy` and `moments`, each run with the correction of every
# refinement event local to its window (the default) and global (PERIADAPT_GLOBAL_REBUILD: every
# family searched and corrected again, as before), REPEATS times each in turn, against the
# uniform fine grid of the same deck. Prints the smallest wall times (summary.json's
# wall_time_s) and their ratios.
#   bash bench/surface_correction_events.sh [REPEATS] [DECK]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
deck=${2:-bench/agrs/three_point_bending_pmb.yaml}
[[ -x build/periadapt ]] || bash scripts/build.sh
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
spacing=$(python3 -c "import re,sys; print(float(re.search(r'(?m)^\s*spacing:\s*([0-9.eE+-]+)', open(sys.argv[1]).read()).group(1)) / 2)" "$deck")
wall() {  # correction, then env words -> wall time
  local sc=$1; shift
  "$@" build/periadapt run "$deck" --quiet --set "output.directory=$out/run" \
    --set "discretization.surface_correction=$sc" > /dev/null
  python3 -c "import json; print(json.load(open('$out/run/summary.json'))['wall_time_s'])"
}
fine() {
  build/periadapt run "$deck" --quiet --set "output.directory=$out/run" --set adapt=null \
    --set "discretization.spacing=$spacing" --set "discretization.surface_correction=$1" > /dev/null
  python3 -c "import json; print(json.load(open('$out/run/summary.json'))['wall_time_s'])"
}
declare -A t
for ((k = 0; k < repeats; ++k)); do
  for sc in energy moments; do
    t[$sc.local]+=" $(wall $sc env)"
    t[$sc.global]+=" $(wall $sc env PERIADAPT_GLOBAL_REBUILD=1)"
    t[$sc.fine]+=" $(fine $sc)"
  done
done
for sc in energy moments; do
  python3 - "$sc" "${t[$sc.local]}" "${t[$sc.global]}" "${t[$sc.fine]}" <<'PY'
import sys
sc, l, g, f = sys.argv[1], *(min(float(v) for v in a.split()) for a in sys.argv[2:5])
print(f"{sc:8s}: local {l:.3f} s, global {g:.3f} s, uniform fine {f:.3f} s; "
      f"local / global {l / g:.3f}, local / fine {l / f:.3f}, global / fine {g / f:.3f}")
PY
done
