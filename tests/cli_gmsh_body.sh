#!/usr/bin/env bash
# Bodies read with libgmsh (discretization.body.gmsh):
# - 2D: examples/curved_notch_plate.geo (100 x 40 mm, a 2 mm slot ending in a 1 mm radius
#   semicircle): the kept nodes are the lattice cell centres inside the analytic outline, up to
#   the centres nearer the arc than the mesh's chord sagitta (0.1 mm chords: 1.3 um);
# - 3D: a 20 x 10 x 5 mm box extruded from a rectangle (a tetrahedral mesh): exactly its cells;
# - a geometry with no surface is refused with exit code 2 and the reason.
set -u
bin="$1"; root="$2"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cp "$root/examples/curved_notch_plate.geo" "$tmp/"
cat > "$tmp/plate.yaml" <<YAML
model: {dimension: 2, thickness: 1.0}
material: {youngs_modulus: 72.0e9, density: 2440.0}
discretization: {spacing: 0.5e-3, body: {gmsh: curved_notch_plate.geo}}
damage: {enabled: false}
solver: {steps: 1}
YAML
"$bin" check "$tmp/plate.yaml" --write-nodes "$tmp/plate.csv" > /dev/null || { echo "FAIL 2D check"; fail=1; }
python3 - "$tmp/plate.csv" <<'PY' || fail=1
import csv, math, sys
got = {(round(float(r["x"]) * 2e4), round(float(r["y"]) * 2e4)) for r in csv.DictReader(open(sys.argv[1]))}
h = 0.5  # mm
def outside_notch(x, y):  # the slot and its semicircular root, lengths in mm
    if x <= 19 and 19 < y < 21:
        return False
    return math.hypot(x - 19, y - 20) >= 1 or x < 19
def near_arc(x, y):
    return x >= 19 and abs(math.hypot(x - 19, y - 20) - 1) < 2e-3
want, ambiguous = set(), 0
for i in range(200):
    for j in range(80):
        x, y = (i + 0.5) * h, (j + 0.5) * h
        ambiguous += near_arc(x, y)
        if outside_notch(x, y):
            want.add((round(x * 20), round(y * 20)))
diff = len(got ^ want)
ok = diff <= ambiguous
print(("ok   " if ok else "FAIL ") + f"2D Gmsh plate: {len(got)} nodes, {len(want)} cell centres outside the analytic notch, {diff} differ ({ambiguous} within the chord sagitta of the arc)")
sys.exit(0 if ok else 1)
PY
cat > "$tmp/box.geo" <<'GEO'
h = 2.0e-3;
Point(1) = {0, 0, 0, h}; Point(2) = {0.02, 0, 0, h}; Point(3) = {0.02, 0.01, 0, h}; Point(4) = {0, 0.01, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Extrude {0, 0, 0.005} { Surface{1}; }
GEO
cat > "$tmp/box.yaml" <<YAML
model: {dimension: 3}
material: {youngs_modulus: 72.0e9, density: 2440.0}
discretization: {spacing: 1.0e-3, body: {gmsh: box.geo}}
damage: {enabled: false}
solver: {steps: 1}
YAML
"$bin" check "$tmp/box.yaml" --write-nodes "$tmp/box.csv" > /dev/null || { echo "FAIL 3D check"; fail=1; }
n=$(($(wc -l < "$tmp/box.csv") - 1))
[[ $n -eq 1000 ]] && echo "ok   3D Gmsh box: $n nodes = 20 x 10 x 5 cells" || { echo "FAIL 3D Gmsh box: $n nodes, not 1000"; fail=1; }
printf 'Point(1) = {0, 0, 0, 1e-3};\nPoint(2) = {0.01, 0, 0, 1e-3};\nLine(1) = {1, 2};\n' > "$tmp/line.geo"
sed 's/curved_notch_plate.geo/line.geo/' "$tmp/plate.yaml" > "$tmp/line.yaml"
"$bin" check "$tmp/line.yaml" > "$tmp/line.log" 2>&1
[[ $? -eq 2 ]] && grep -q "no triangles" "$tmp/line.log" && echo "ok   refused: a geometry without a surface" ||
  { echo "FAIL geometry without a surface: $(head -2 "$tmp/line.log")"; fail=1; }
exit $fail
