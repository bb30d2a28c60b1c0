#!/usr/bin/env bash
# A body read from a closed CAD surface (discretization.body.surface): the bracket of
# scripts/make_bracket_stl.py, an L-outline with a 45-degree chamfer extruded 15 mm.
# - The kept nodes are exactly the lattice cell centres inside the outline (an independent
#   point-in-polygon count, points on the surface inside).
# - Their volumes sum to the CAD volume, 8730 mm^3, within the half-cell error of the cells the
#   oblique chamfer face cuts: area 6 sqrt(2) x 15 mm^2 times dx / 2 (63.6 mm^3 at 1 mm, 31.8 at
#   0.5 mm); every other face lies on cell boundaries.
# - An open surface and a surface in 2D are refused with exit code 2 and the reason.
set -u
bin="$1"; root="$2"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
python3 "$root/scripts/make_bracket_stl.py" "$tmp/bracket.stl"
for dx in 1.0e-3 0.5e-3; do
  cat > "$tmp/d.yaml" <<YAML
model: {dimension: 3}
material: {youngs_modulus: 70.0e9, density: 2700.0}
discretization: {spacing: $dx, body: {surface: bracket.stl}}
damage: {enabled: false}
solver: {steps: 1}
YAML
  "$bin" check "$tmp/d.yaml" --write-nodes "$tmp/nodes.csv" > /dev/null || { echo "FAIL check at $dx"; fail=1; continue; }
  python3 - "$tmp/nodes.csv" "$dx" <<'PY' || fail=1
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
dx = float(sys.argv[2])
outline = [(6, 0), (40, 0), (40, 10), (10, 10), (10, 30), (0, 30), (0, 6)]
def inside(x, y):  # even-odd rule, points on an edge inside
    for (ax, ay), (bx, by) in zip(outline, outline[1:] + outline[:1]):
        cr = (bx - ax) * (y - ay) - (by - ay) * (x - ax)
        if abs(cr) < 1e-9 and min(ax, bx) - 1e-9 <= x <= max(ax, bx) + 1e-9 and min(ay, by) - 1e-9 <= y <= max(ay, by) + 1e-9:
            return True
    c = False
    for (ax, ay), (bx, by) in zip(outline, outline[1:] + outline[:1]):
        if (ay > y) != (by > y) and x < (bx - ax) * (y - ay) / (by - ay) + ax:
            c = not c
    return c
h = dx * 1e3
n = round(40 / h), round(30 / h), round(15 / h)
expected = n[2] * sum(inside((i + 0.5) * h, (j + 0.5) * h) for i in range(n[0]) for j in range(n[1]))
volume = sum(float(r["volume"]) for r in rows) * 1e9  # mm^3
bound = 6 * math.sqrt(2) * 15 * h / 2
ok_n = len(rows) == expected
ok_v = abs(volume - 8730) <= bound
print(("ok   " if ok_n else "FAIL ") + f"dx {h} mm: {len(rows)} nodes, {expected} cell centres inside the outline")
print(("ok   " if ok_v else "FAIL ") + f"dx {h} mm: node volumes {volume:.2f} mm^3 against 8730 (error {volume - 8730:+.2f}, bound {bound:.1f})")
sys.exit(0 if ok_n and ok_v else 1)
PY
done
# An open surface: the bracket without its last facet.
python3 - "$tmp/bracket.stl" "$tmp/open.stl" <<'PY'
import sys
text = open(sys.argv[1]).read()
cut = text.rfind("  facet normal")
open(sys.argv[2], "w").write(text[:cut] + "endsolid bracket\n")
PY
sed 's/bracket.stl/open.stl/' "$tmp/d.yaml" > "$tmp/open.yaml"
"$bin" check "$tmp/open.yaml" > "$tmp/open.log" 2>&1
[[ $? -eq 2 ]] && grep -q "not closed" "$tmp/open.log" && echo "ok   refused: an open surface" ||
  { echo "FAIL open surface: $(head -2 "$tmp/open.log")"; fail=1; }
cat > "$tmp/flat.yaml" <<YAML
model: {dimension: 2}
material: {youngs_modulus: 70.0e9, density: 2700.0}
discretization: {spacing: 1.0e-3, body: {surface: bracket.stl}}
damage: {enabled: false}
solver: {steps: 1}
YAML
"$bin" check "$tmp/flat.yaml" > "$tmp/flat.log" 2>&1
[[ $? -eq 2 ]] && grep -q "for 3D models" "$tmp/flat.log" && echo "ok   refused: a surface in 2D" ||
  { echo "FAIL surface in 2D: $(head -2 "$tmp/flat.log")"; fail=1; }
exit $fail
