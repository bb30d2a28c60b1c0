#!/usr/bin/env bash
# output.regions: sums over named regions in history.csv and summary.json, checked against
# mechanics. A plate pulled at its right edge and held at its left, relaxed to equilibrium:
# - the right half's net internal force balances the load it carries (relaxation tolerance
#   1e-9, bound 1e-6 of the load);
# - the two halves' internal forces are equal and opposite, and the whole body's sums to zero
#   (pairwise bond forces, bound 1e-9 of the load);
# - the halves' strain energies add up to the whole's, which is history.csv's strain energy
#   (the same densities, bound 1e-12 relative).
# An explicit run with an initial velocity field: the whole body's kinetic energy is
# history.csv's (bound 1e-12 relative). A region that selects no node is refused (exit 2).
set -u
bin="$1"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
deck() {  # solver extra-initial-conditions
  cat <<YAML
model: {dimension: 2, plane: stress, thickness: 0.01}
material: {youngs_modulus: 200.0e9, density: 7850.0}
discretization:
  spacing: 0.01
  body: {box: {min: [0.0, 0.0], max: [0.4, 0.1]}}
loads:
  - {name: pull, type: traction, region: {box: {min: [0.39, 0.0], max: [0.4, 0.1]}}, value: [50.0e6, 5.0e6]}
boundary_conditions:
  - {name: wall, region: {box: {min: [0.0, 0.0], max: [0.01, 0.1]}}, displacement: [0.0, 0.0]}
$2
damage: {enabled: false}
solver: $1
output:
  directory: $tmp/out
  history_every: 5
  regions:
    - {name: left, region: {box: {min: [0.0, 0.0], max: [0.2, 0.1]}}}
    - {name: right, region: {box: {min: [0.2, 0.0], max: [0.4, 0.1]}}}
    - {name: all, region: {box: {min: [-1, -1], max: [1, 1]}}}
YAML
}
deck "{type: relaxation, tolerance: 1.0e-9}" "" > "$tmp/relax.yaml"
"$bin" run "$tmp/relax.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL relaxation run"; fail=1; }
python3 - "$tmp/out" <<'PY' || fail=1
import csv, json, sys
out = sys.argv[1]
row = list(csv.DictReader(open(f"{out}/history.csv")))[-1]
reg = json.load(open(f"{out}/summary.json"))["regions"]
F = [float(row["load_pull_fx_N"]), float(row["load_pull_fy_N"])]
scale = max(abs(c) for c in F)
ok = True
def check(name, err, bound):
    global ok
    good = err <= bound
    ok &= good
    print(("ok   " if good else "FAIL ") + f"{name}: {err:.2e} (bound {bound:g})")
check("right half's internal force + its load",
      max(abs(float(row[f"region_right_f{a}_N"]) + F[d]) for d, a in enumerate("xy")) / scale, 1e-6)
check("left + right internal forces",
      max(abs(float(row[f"region_left_f{a}_N"]) + float(row[f"region_right_f{a}_N"])) for a in "xy") / scale, 1e-9)
check("whole body's internal force", max(abs(float(row[f"region_all_f{a}_N"])) for a in "xy") / scale, 1e-9)
U = float(row["strain_energy_J"])
check("whole body's strain energy against history's", abs(float(row["region_all_strain_energy_J"]) / U - 1), 1e-12)
check("left + right strain energy against the whole's",
      abs((reg["left"]["strain_energy_J"] + reg["right"]["strain_energy_J"]) / reg["all"]["strain_energy_J"] - 1), 1e-12)
sys.exit(0 if ok else 1)
PY
deck "{steps: 20}" 'initial_conditions: {velocity: ["3*x", "-2*y"]}' > "$tmp/explicit.yaml"
"$bin" run "$tmp/explicit.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL explicit run"; fail=1; }
python3 - "$tmp/out" <<'PY' || fail=1
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/history.csv")))
err = max(abs(float(r["region_all_kinetic_energy_J"]) / float(r["kinetic_energy_J"]) - 1) for r in rows)
print(("ok   " if err <= 1e-12 else "FAIL ") + f"whole body's kinetic energy against history's: {err:.2e} over {len(rows)} rows")
sys.exit(0 if err <= 1e-12 else 1)
PY
sed -e 's/max: \[1, 1\]}}}/max: [1, 1]}}}\n    - {name: nowhere, region: {box: {min: [2, 2], max: [3, 3]}}}/' "$tmp/relax.yaml" > "$tmp/empty.yaml"
"$bin" run "$tmp/empty.yaml" --quiet > "$tmp/empty.log" 2>&1
rc=$?
if [[ $rc -eq 2 ]] && grep -q "output.regions\[3\].region" "$tmp/empty.log"; then
  echo "ok   an empty output region is refused: $(head -1 "$tmp/empty.log")"
else
  echo "FAIL an empty output region: exit $rc, $(head -2 "$tmp/empty.log")"; fail=1
fi
exit $fail
