#!/usr/bin/env bash
# Reactions of static and relaxation runs (summary.json "resultants", history.csv columns):
# a cantilever plate held at one edge and pulled at the other is in equilibrium, so the wall's
# reaction balances the applied traction. The linear static solve balances it to its solver
# residual (bound 1e-8 relative); dynamic relaxation to its tolerance (1e-7 here, bound 1e-6).
set -u
bin="$1"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ok() { echo "ok   $*"; }
bad() { echo "FAIL $*"; fail=1; }
deck() {  # solver line
  cat <<YAML
model: {dimension: 2, plane: stress, thickness: 0.01}
material: {youngs_modulus: 200.0e9, density: 7850.0}
discretization:
  spacing: 0.01
  registration: node_on_edge
  body: {box: {min: [0.0, 0.0], max: [0.3, 0.1]}}
loads:
  - {name: tip, type: traction, region: {box: {min: [0.3, 0.0], max: [0.3, 0.1]}}, value: [50.0e6, 2.0e6]}
boundary_conditions:
  - {name: wall, region: {box: {min: [0.0, 0.0], max: [0.0, 0.1]}}, displacement: [0.0, 0.0]}
damage: {enabled: false}
solver: $1
output: {directory: $tmp/out, load_displacement: {name: wall, component: x}}
YAML
}
check() {  # name bound
  python3 - "$tmp/out/summary.json" "$2" <<'PY' && ok "$1" || bad "$1"
import json, sys
r = json.load(open(sys.argv[1]))['resultants']
F = r['loads']['tip']['force_N']; R = r['boundary_conditions']['wall']['reaction_N']
err = max(abs(F[d] + R[d]) for d in range(2)) / max(abs(F[0]), abs(F[1]))
print('  applied', F, 'reaction', R, 'imbalance %.2e' % err)
sys.exit(0 if abs(F[0] - 50.0e6 * 0.1 * 0.01) < 1e-9 * 5e4 and err <= float(sys.argv[2]) else 1)
PY
}
deck "{type: static}" > "$tmp/static.yaml"
"$bin" run "$tmp/static.yaml" --quiet > /dev/null 2>&1 || bad "static run"
check "static: the wall's reaction balances the traction to 1e-8" 1e-8
deck "{type: relaxation, load_steps: 2, tolerance: 1.0e-7}" > "$tmp/relax.yaml"
"$bin" run "$tmp/relax.yaml" --quiet > /dev/null 2>&1 || bad "relaxation run"
check "relaxation: the wall's reaction balances the traction to 1e-6" 1e-6
head -1 "$tmp/out/history.csv" | grep -q "bc_wall_fx_N" && [[ $(wc -l < "$tmp/out/history.csv") -eq 3 ]] &&
  ok "relaxation history: a reaction column, one row per load step" || bad "relaxation history columns"
[[ -s $tmp/out/load_displacement.png ]] && ok "relaxation: load_displacement.png" || bad "no load_displacement.png"
exit $fail
