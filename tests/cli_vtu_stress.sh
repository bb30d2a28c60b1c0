#!/usr/bin/env bash
# output.stress: the VTU read back with meshio (Debian python3-meshio) carries per-node stress
# and strain tensors (and the LPS dilatation) that describe a plate in uniaxial tension:
# - mean stress over the mid-span cross-section = the applied traction within 1% (equilibrium of
#   the section; measured 1.0001);
# - strain_xx E / traction within 2% with the moments correction (the uncorrected PMB plate, 10
#   nodes deep, is 23% soft);
# - LPS (nu = 1/4, relaxed): dilatation (1 - nu) traction / E within 2% in the mid-span column.
# And output.vtu_compression: zlib gives the same arrays bit for bit.
set -u
bin="$1"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
py=python3
for p in /usr/bin/python3 python3; do "$p" -c "import meshio" 2> /dev/null && { py=$p; break; }; done
deck() {  # formulation-and-material solver
  cat <<YAML
model: {dimension: 2, plane: stress, thickness: 0.01$1}
material: {youngs_modulus: 200.0e9, density: 7850.0$2}
discretization:
  spacing: 0.01
  surface_correction: moments
  body: {box: {min: [0.0, 0.0], max: [0.4, 0.1]}}
loads:
  - {name: pull, type: traction, region: {box: {min: [0.39, 0.0], max: [0.4, 0.1]}}, value: [50.0e6, 0.0]}
boundary_conditions:
  - {name: wall, region: {box: {min: [0.0, 0.0], max: [0.01, 0.1]}}, displacement: [0.0, null]}
  - {name: pin, region: {box: {min: [0.0, 0.0], max: [0.01, 0.01]}}, displacement: [null, 0.0]}
damage: {enabled: false}
solver: $3
output: {directory: $tmp/out$4, stress: true$5}
YAML
}
deck "" "" "{type: static}" pmb "" > "$tmp/pmb.yaml"
deck "" "" "{type: static}" zlib ", vtu_compression: zlib" > "$tmp/zlib.yaml"
deck ", formulation: lps" ", poisson_ratio: 0.25" "{type: relaxation, tolerance: 1.0e-9}" lps "" > "$tmp/lps.yaml"
"$bin" run "$tmp/pmb.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL pmb static run"; fail=1; }
"$bin" run "$tmp/lps.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL lps relaxation run"; fail=1; }
"$bin" run "$tmp/zlib.yaml" --quiet > /dev/null 2>&1 || { echo "FAIL zlib static run"; fail=1; }
"$py" - "$tmp" <<'PY' || fail=1
import sys
import meshio
import numpy as np
tmp, T, E, nu = sys.argv[1], 50.0e6, 200.0e9, 0.25
ok = True
def check(name, value, target, tol):
    global ok
    good = abs(value / target - 1) <= tol
    ok &= good
    print(("ok   " if good else "FAIL ") + f"{name}: {value / target:.5f} of the expected, bound 1 +- {tol}")
pmb = meshio.read(f"{tmp}/outpmb/snapshot_00000.vtu")
n = len(pmb.points)
shapes = {k: v.shape for k, v in pmb.point_data.items()}
good = shapes.get("stress") == (n, 9) and shapes.get("strain") == (n, 9) and "dilatation" not in shapes
ok &= good
print(("ok   " if good else "FAIL ") + f"PMB fields: {sorted(shapes)}")
col = np.abs(pmb.points[:, 0] - 0.205) < 1e-6
check("PMB mid-span mean stress_xx / traction", pmb.point_data["stress"][col, 0].mean(), T, 0.01)
check("PMB mid-span mean strain_xx E / traction", pmb.point_data["strain"][col, 0].mean() * E, T, 0.02)
import glob
lps = meshio.read(sorted(glob.glob(f"{tmp}/outlps/snapshot_*.vtu"))[-1])
col = np.abs(lps.points[:, 0] - 0.205) < 1e-6
check("LPS mid-span mean stress_xx / traction", lps.point_data["stress"][col, 0].mean(), T, 0.01)
check("LPS mid-span dilatation E / ((1 - nu) traction)", lps.point_data["dilatation"][col].mean(),
      (1 - nu) * T / E, 0.02)
z = meshio.read(f"{tmp}/outzlib/snapshot_00000.vtu")
same = set(z.point_data) == set(pmb.point_data) and np.array_equal(z.points, pmb.points) and all(
    np.array_equal(z.point_data[k], pmb.point_data[k]) for k in pmb.point_data)
ok &= same
print(("ok   " if same else "FAIL ") + "zlib-compressed VTU: the same arrays bit for bit")
sys.exit(0 if ok else 1)
PY
exit $fail
