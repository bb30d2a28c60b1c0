#!/usr/bin/env bash
# Ghost forces at level interfaces, by pairing: runs bench/interface/uniform_strain_patch.yaml one
# step in each bond pairing (and formulation, given as extra --set words) and prints, per level,
# the largest acceleration of the nodes at least 6 mm (two horizons) from the free edges, as
# |a| and as rho |a| delta / (E eps), the ghost force density in units of a strain jump of the
# applied size across one coarse horizon.
#   bash bench/interface/patch_test.sh [--set key=value ...]   (e.g. --set adapt.interface_fit=true)
set -euo pipefail
cd "$(dirname "$0")/../.."
[[ -x build/periadapt ]] || bash scripts/build.sh
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
for p in ${PAIRINGS:-source_horizon dual_horizon}; do
  build/periadapt run bench/interface/uniform_strain_patch.yaml --out "$out/$p" --quiet \
    --set solver.bond_pairing=$p "$@" > /dev/null 2> "$out/$p.err" ||
    echo "$p: $(cat "$out/$p.err")"
done
/usr/bin/python3 - "$out" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.getcwd(), "scripts", "agrs"))
from vtu import read_vtu
out = sys.argv[1]
for p in ("source_horizon", "dual_horizon"):
    if not os.path.exists(os.path.join(out, p, "summary.json")): continue
    f = read_vtu(os.path.join(out, p, "snapshot_00001.vtu"))
    dt = json.load(open(os.path.join(out, p, "summary.json")))["dt"]
    fine = [x for x, l in zip(f["Points"], f["refinement_level"]) if l > 0]
    lo = [min(x[d] for x in fine) for d in (0, 1)]
    hi = [max(x[d] for x in fine) for d in (0, 1)]
    worst = {}
    for x, v, l in zip(f["Points"], f["velocity"], f["refinement_level"]):
        if min(x[0], x[1], 0.06 - x[0], 0.06 - x[1]) < 0.006: continue
        a = (v[0] ** 2 + v[1] ** 2) ** 0.5 / dt  # one Velocity-Verlet step from rest
        # Coarse nodes two horizons or more from the patch: the uniform grid's own error.
        gap = max(max(lo[d] - x[d], x[d] - hi[d]) for d in (0, 1))
        key = "level 1" if l > 0 else ("level 0, far" if gap >= 0.006 else "level 0, near")
        worst[key] = max(worst.get(key, 0.0), a)
    for k in sorted(worst):
        print(f"{p:15s} {k:14s}: max |a| {worst[k]:.3e} m/s^2, "
              f"rho |a| delta / (E eps) = {2440 * worst[k] * 0.003 / (72e9 * 1e-4):.3f}")
PY
