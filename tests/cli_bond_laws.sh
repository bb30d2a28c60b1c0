#!/usr/bin/env bash
# The history laws in whole runs (issue 22's acceptance for the two new laws):
# - bilinear softening, examples/softening_bar_1d.yaml: the energy the crack dissipates
#   (external work - strain - kinetic energy at the end) equals G0 A within 2%, and exactly the
#   72 directed bonds that cross the middle break (m = 8: 2 (1 + ... + 8)). The discrete crossing
#   sum of the PA quadrature is itself 0.78% above the continuum's G0 at m = 8
#   ((1^2 + ... + 7^2 + 8^2 / 2) / (8^3 / 3) = 1.0078; the dissipation measured is 1.0083).
# - the same bar refined to level 1 everywhere before the run (delta scaling) dissipates what the
#   uniform grid of half the spacing does (children's breaking stretch, micromodulus and volumes),
#   to 1e-9 relative; refined by the stretch trigger in the dual-horizon pairing it dissipates
#   G0 A within 2% (1.0088; the source-horizon pairing's level interface adds 6%, docs/agrs.md).
# - elastic-perfectly plastic, examples/plastic_bar_1d.yaml: the yield plateau is sigma_Y A (1%)
#   and the unloading branch crosses zero force at the hand-calculated permanent set
#   U_max - F(U_max) / k, k the loading slope (1%: the loading is quasi-static, 400 wave transits,
#   and the fitted slope carries the start-up ripple).
# - the static solve: below yield it is PMB's solve (same displacements, bit for bit); past the
#   onset it is refused (exit 2, solver.type). A yield stress whose stretch is at or above the
#   brittle critical stretch is refused (exit 2, material.yield_stress).
# - restart from a checkpoint taken during plastic flow continues bit for bit.
# - AGRS: an adaptive 2D run of the plastic law refines ahead of its crack: it cracks and no
#   coarse node cracks.
set -u
bin="$1"; examples="$2"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
run() {  # deck out [--set ...]
  local deck=$1 out=$2; shift 2
  "$bin" run "$deck" --quiet --set "output.directory=$out" "$@" > "$tmp/log" 2>&1
}
dissipated() {  # out -> (W - K - U at the end) - (W - K at the start), and broken bonds
  python3 - "$1" <<'PY'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1] + "/history.csv")))
e = lambda x: float(x["external_work_J"]) - float(x["kinetic_energy_J"])
print(e(r[-1]) - float(r[-1]["strain_energy_J"]) - e(r[0]), r[-1]["broken_bonds"])
PY
}
soft="$examples/softening_bar_1d.yaml"
run "$soft" "$tmp/soft" || { echo "FAIL softening bar run"; cat "$tmp/log"; fail=1; }
read -r D broken <<< "$(dissipated "$tmp/soft")"
python3 -c "import sys; r = $D / (100.0 * 1e-4); print(f'softening bar: dissipated / (G0 A) = {r:.5f}, broken bonds $broken'); sys.exit(0 if abs(r - 1) < 0.02 and $broken == 72 else 1)" || { echo "FAIL dissipated energy"; fail=1; }

run "$soft" "$tmp/fine" --set discretization.spacing=0.25e-3 \
    --set "damage.no_fail=[{box: {min: [-0.05], max: [-0.002]}}, {box: {min: [0.002], max: [0.05]}}]" || { echo "FAIL fine bar"; fail=1; }
run "$soft" "$tmp/refined" \
    --set "damage.no_fail=[{box: {min: [-0.05], max: [-0.002]}}, {box: {min: [0.002], max: [0.05]}}]" \
    --set "adapt={max_level: 1, initial_refinement: [{region: {box: {min: [-1], max: [1]}}, level: 1}], stretch_trigger: null, damage_trigger: false}" \
  || { echo "FAIL refined bar"; cat "$tmp/log"; fail=1; }
read -r Df bf <<< "$(dissipated "$tmp/fine")"
read -r Dr br <<< "$(dissipated "$tmp/refined")"
python3 -c "import sys; print(f'refined everywhere / uniform fine: {$Dr / $Df:.12f} ({$Df / 0.01:.5f} G0 A)'); sys.exit(0 if abs($Dr / $Df - 1) < 1e-9 and $br == $bf else 1)" || { echo "FAIL refined bar differs from the fine grid"; fail=1; }
# Refined where the stretch trigger asks, in the dual-horizon pairing (equal and opposite pair
# forces across the level interface): the crack still dissipates G0 A within 2%.
run "$soft" "$tmp/adaptive" \
    --set "damage.no_fail=[{box: {min: [-0.05], max: [-0.002]}}, {box: {min: [0.002], max: [0.05]}}]" \
    --set "adapt={max_level: 1}" --set solver.bond_pairing=dual_horizon || { echo "FAIL adaptive bar"; cat "$tmp/log"; fail=1; }
read -r Da ba <<< "$(dissipated "$tmp/adaptive")"
python3 -c "import sys; r = $Da / 0.01; print(f'adaptive dual-horizon bar: dissipated / (G0 A) = {r:.5f}, broken bonds $ba'); sys.exit(0 if abs(r - 1) < 0.02 and $ba == 72 else 1)" || { echo "FAIL adaptive bar dissipation"; fail=1; }

run "$examples/plastic_bar_1d.yaml" "$tmp/plastic" || { echo "FAIL plastic bar run"; fail=1; }
python3 - "$tmp/plastic" <<'PY' || fail=1
import csv, sys
r = list(csv.DictReader(open(sys.argv[1] + "/history.csv")))
F = [float(x["bc_right_fx_N"]) for x in r]
u = [float(x["bc_right_ux_m"]) for x in r]
top = max(range(len(u)), key=lambda i: u[i])
fy = 1.0e6 * 1.0e-4
pts = [(u[i], F[i]) for i in range(1, top) if F[i] < 0.8 * fy]
k = sum(a * b for a, b in pts) / sum(a * a for a, b in pts)
cross = None
for i in range(top, len(F) - 1):
    if F[i] > 0 >= F[i + 1]:
        cross = u[i] + F[i] / (F[i] - F[i + 1]) * (u[i + 1] - u[i])
        break
hand = u[top] - F[top] / k
print(f"plastic bar: plateau {F[top]:.4f} N (sigma_Y A = {fy:.1f}), permanent set {cross:.6e} m, "
      f"hand {hand:.6e} m, ratio {cross / hand:.5f}")
ok = abs(F[top] / fy - 1) < 0.01 and cross is not None and abs(cross / hand - 1) < 0.01
sys.exit(0 if ok else 1)
PY

# Restart: the plastic bar's checkpoint at step 40000 (in compressive flow) continues to the
# uninterrupted run's history, bit for bit (all but the wall-time column).
run "$examples/plastic_bar_1d.yaml" "$tmp/ck" --set output.checkpoint_every=20000 || { echo "FAIL checkpointed run"; fail=1; }
"$bin" run "$examples/plastic_bar_1d.yaml" --quiet --set "output.directory=$tmp/restarted" \
    --restart "$tmp/ck/checkpoint.bin" > "$tmp/log" 2>&1 || { echo "FAIL restart"; cat "$tmp/log"; fail=1; }
if cmp -s <(sed 's/,[^,]*$//' "$tmp/ck/history.csv") <(sed 's/,[^,]*$//' "$tmp/restarted/history.csv"); then
  echo "restart of the plastic bar: history bit for bit"
else echo "FAIL restarted plastic bar differs"; fail=1; fi

plate() {  # formulation-and-keys traction
  cat <<YAML
model: {dimension: 2, plane: stress, thickness: 0.01, formulation: $1}
material: {youngs_modulus: 1.0e9, density: 1000.0, fracture_energy: 100.0$2}
discretization: {spacing: 0.002, body: {box: {min: [0.0, 0.0], max: [0.1, 0.04]}}}
loads:
  - {name: pull, type: traction, region: {box: {min: [0.098, 0.0], max: [0.1, 0.04]}}, value: [$3, 0.0]}
boundary_conditions:
  - {name: wall, region: {box: {min: [0.0, 0.0], max: [0.002, 0.04]}}, displacement: [0.0, 0.0]}
solver: {type: static}
output: {directory: $tmp/static}
YAML
}
plate pmb "" 1.0e5 > "$tmp/pmb.yaml"
plate elastic_perfectly_plastic ", yield_stress: 1.0e6" 1.0e5 > "$tmp/epp.yaml"
plate elastic_perfectly_plastic ", yield_stress: 1.0e6" 5.0e6 > "$tmp/epp_far.yaml"
plate elastic_perfectly_plastic ", yield_stress: 1.0e9" 1.0e5 > "$tmp/epp_high.yaml"
"$bin" run "$tmp/pmb.yaml" --quiet > /dev/null 2>&1 && cp "$tmp/static/displacement.csv" "$tmp/pmb.csv"
"$bin" run "$tmp/epp.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL static plastic plate below yield"; fail=1; }
cmp -s "$tmp/pmb.csv" "$tmp/static/displacement.csv" && echo "static solve below yield: PMB's displacements bit for bit" ||
  { echo "FAIL static plastic plate differs from PMB"; fail=1; }
refused() {  # deck key
  "$bin" run "$1" --quiet > "$tmp/err" 2>&1
  local rc=$?
  if [[ $rc == 2 ]] && grep -q "$2" "$tmp/err"; then echo "refused ($2): $(head -c 160 "$tmp/err")"
  else echo "FAIL $1: exit $rc, expected 2 naming $2"; cat "$tmp/err"; fail=1; fi
}
refused "$tmp/epp_far.yaml" "solver.type"
refused "$tmp/epp_high.yaml" "material.yield_stress"

# AGRS with the plastic law: the V-notch plate example, adaptive.
run "$examples/v_notch_2d.yaml" "$tmp/adapt" --set model.formulation=elastic_perfectly_plastic \
    --set material.yield_stress=90.0e6 --set "adapt={max_level: 1}" --set solver.end_time=20.0e-6 ||
  { echo "FAIL adaptive plastic run"; cat "$tmp/log"; fail=1; }
python3 - "$tmp/adapt" <<'PY' || fail=1
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
a, n = s["adapt"], s["nodes"]
print(f"adaptive plastic V-notch: {a['events']} events, nodes {n['initial']} -> {n['final']}, "
      f"{a['cracked_nodes']} cracked nodes, {a['cracked_coarse_nodes']} of them coarse")
sys.exit(0 if a["events"] > 0 and a["cracked_nodes"] > 0 and a["cracked_coarse_nodes"] == 0 else 1)
PY
exit $fail
