#!/usr/bin/env bash
# Refined zones at a hole (docs/agrs.md, "Refined zones at curved boundaries"): the suite's plate
# with a hole (bench/agrs/plate_hole_pmb.yaml) on the uniform 0.25 mm grid; with level 1
# everywhere and a fixed level-2 zone beside the hole (no triggers); and with the automatic
# profile at max_level 2; the last two with and without adapt.fill_boundary_cells. Prints each
# run's first broken bond, damage sum and final nodes.
#   [PERIADAPT=path/to/periadapt] bash bench/agrs/curved_boundary.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${PERIADAPT:-build/periadapt}
[[ -x $bin ]] || bash scripts/build.sh
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
src=bench/agrs/plate_hole_pmb.yaml
zones='initial_refinement: [{region: {box: {min: [0.0, 0.0], max: [0.05, 0.05]}}, level: 1}, {region: {box: {min: [0.018, 0.021], max: [0.032, 0.029]}}, level: 2}]'
sed 's/^adapt:.*$//; s/spacing: 1.0e-3/spacing: 0.25e-3/' $src > "$out/uniform_0.25mm.yaml"
for fill in false true; do
  sed "s/^adapt:.*$/adapt: {max_level: 2, visibility: false, fill_boundary_cells: $fill, $zones}/" \
    $src > "$out/fixed_zone_fill_$fill.yaml"
  sed "s/^adapt:.*$/adapt: {max_level: 2, fill_boundary_cells: $fill}/" $src > "$out/profile_fill_$fill.yaml"
done
for case in uniform_0.25mm fixed_zone_fill_false fixed_zone_fill_true profile_fill_false profile_fill_true; do
  "$bin" run "$out/$case.yaml" --out "$out/$case" --quiet > /dev/null
  python3 - "$out/$case" "$case" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + '/history.csv')))
first = next((float(r['time_s']) * 1e6 for r in rows if float(r['broken_bonds']) > 0), None)
print(f"{sys.argv[2]:22s} first break {'none' if first is None else f'{first:.2f} us':>10s}, "
      f"damage sum {float(rows[-1]['damage_sum']):7.1f}, nodes {rows[-1]['nodes']}")
PY
done
