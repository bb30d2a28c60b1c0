#!/usr/bin/env bash
# Cost of a large linear static solve next to one explicit step of the same model: the thesis 4.1
# plate (1 m x 0.5 m, 200 MPa, E = 200 GPa, plane stress) on a ~200,000-node grid (m = 3.015,
# IPA-Hybrid areas). Prints both times and their ratio (same script, same machine state).
# Usage: bench/static_vs_explicit.sh [SPACING]   (default 1/632 m -> 633 x 317 = 200,661 nodes)
set -euo pipefail
cd "$(dirname "$0")/.."
h="${1:-0.0015822784810126582}"  # 1/632: nodes on the edges and on both symmetry axes
[[ -x build/periadapt ]] || bash scripts/build.sh
work=$(mktemp -d /tmp/pa-static.XXXXXX)
delta=$(awk -v h="$h" 'BEGIN { printf "%.9g", 3.015 * h }')
sed -e "s/spacing: 0.01/spacing: $h/" -e "s/horizon: 0.03015/horizon: $delta/" \
    -e "s/quadrature: subcell/quadrature: ipa_hybrid/" -e "s#directory: .*#directory: $work/static#" \
    examples/static_plate_2d.yaml > "$work/static.yaml"
# The same model stepped explicitly (no constraints needed for timing; loads as in the deck).
sed -e '/^boundary_conditions:/,/^damage:/{/^damage:/!d}' \
    -e 's/^  type: static/  type: explicit\n  steps: 20/' -e "s#$work/static#$work/explicit#" \
    "$work/static.yaml" > "$work/explicit.yaml"
sed -i 's/^output:/output:\n  vtu: false\n  history_every: 1000/' "$work/explicit.yaml"
./build/periadapt run "$work/static.yaml" --quiet > /dev/null
./build/periadapt run "$work/explicit.yaml" --quiet > /dev/null
num() { grep -m1 "\"$2\"" "$1" | sed -E 's/.*: *([-0-9.eE+]+).*/\1/'; }
nodes=$(num "$work/static/summary.json" initial)
assemble=$(num "$work/static/summary.json" assemble_time_s)
solve=$(num "$work/static/summary.json" solve_time_s)
steps=$(num "$work/explicit/summary.json" steps)
tsolver=$(num "$work/explicit/summary.json" solver_time_s)
awk -v n="$nodes" -v a="$assemble" -v s="$solve" -v st="$steps" -v ts="$tsolver" 'BEGIN {
  step = ts / st
  printf "nodes %d: static assembly %.2f s + solve %.2f s; explicit step %.4f s; static = %.0f explicit steps\n",
         n, a, s, step, (a + s) / step }'
rm -rf "$work"
