#!/usr/bin/env bash
# discretization.body.points: a point-cloud body. The crack-branching example's lattice written
# by `check --write-nodes` and read back as points reproduces the box-built run bit for bit
# (history.csv less its wall times, every VTU snapshot, summary's broken bonds). Bad point files
# are refused with exit code 2, naming the file and line.
set -u
bin="$1"; example="$2"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cp "$example" "$tmp/box.yaml"
"$bin" check "$tmp/box.yaml" --write-nodes "$tmp/nodes.csv" > /dev/null || { echo "FAIL check --write-nodes"; fail=1; }
python3 - "$tmp" <<'PY'
import re, sys
tmp = sys.argv[1]
s = open(f"{tmp}/box.yaml").read()
s, n = re.subn(r"(\n  body:\n)    box: \{[^\n]*\}", r"\1    points: nodes.csv", s)
assert n == 1, "the example's body box was not found"
open(f"{tmp}/points.yaml", "w").write(s)
PY
"$bin" run "$tmp/box.yaml" --out "$tmp/box" --quiet > /dev/null 2>&1 || { echo "FAIL box run"; fail=1; }
"$bin" run "$tmp/points.yaml" --out "$tmp/points" --quiet > /dev/null 2>&1 || { echo "FAIL points run"; fail=1; }
python3 - "$tmp" <<'PY' || fail=1
import csv, filecmp, glob, json, os, sys
tmp = sys.argv[1]
a = list(csv.DictReader(open(f"{tmp}/box/history.csv")))
b = list(csv.DictReader(open(f"{tmp}/points/history.csv")))
cols = [k for k in a[0] if k != "wall_time_s"]
same_hist = len(a) == len(b) and len(a) > 10 and all(x[k] == y[k] for x, y in zip(a, b) for k in cols)
vtus = sorted(glob.glob(f"{tmp}/box/snapshot_*.vtu"))
same_vtu = len(vtus) > 1 and all(
    filecmp.cmp(v, f"{tmp}/points/{os.path.basename(v)}", shallow=False) for v in vtus)
ja, jb = (json.load(open(f"{tmp}/{d}/summary.json")) for d in ("box", "points"))
same_broken = ja["broken_bonds"] == jb["broken_bonds"] > 0
for ok, what in ((same_hist, f"history.csv, {len(a)} rows"), (same_vtu, f"{len(vtus)} VTU snapshots"),
                 (same_broken, f"broken bonds {ja['broken_bonds']}")):
    print(("ok   " if ok else "FAIL ") + "point cloud = box, bit for bit: " + what)
sys.exit(0 if same_hist and same_vtu and same_broken else 1)
PY
bad() {  # name file-content expected-message-part
  printf '%b' "$2" > "$tmp/bad.csv"
  sed 's|points: nodes.csv|points: bad.csv|' "$tmp/points.yaml" > "$tmp/bad.yaml"
  "$bin" check "$tmp/bad.yaml" > "$tmp/bad.log" 2>&1
  local rc=$?
  if [[ $rc -eq 2 ]] && grep -q -- "$3" "$tmp/bad.log"; then echo "ok   refused: $1"
  else echo "FAIL $1: exit $rc, $(head -2 "$tmp/bad.log")"; fail=1; fi
}
bad "header of another dimension" 'x,y,z,volume\n0,0,0,1\n' "bad.csv:1: the header must be 'x,y,volume'"
bad "a word for a number, with its line" 'x,y,volume\n0,0,1e-7\n0.001,abc,1e-7\n' "bad.csv:3: 'abc' in column y"
bad "a negative volume" 'x,y,volume\n0,0,-1\n' "bad.csv:2: the volume must be > 0"
bad "a short row" 'x,y,volume\n0,0\n' "bad.csv:2: 2 values where the header has 3"
bad "no points" 'x,y,volume\n' "no points after the header"
bad "a repeated row" 'x,y,volume\n0,0,1e-7\n0.001,0,1e-7\n0,0,1e-7\n' "bad.csv:4: the point lies 0 m from the point on line 2"
bad "a point 1e-11 m from another" 'x,y,volume\n0,0,1e-7\n0.00100000001,0,1e-7\n0.001,0,1e-7\n' "bad.csv:4: the point lies 1e-11 m from the point on line 3"
bad "a volume of 1e300" 'x,y,volume\n0,0,1e-7\n0.001,0,1e300\n' "bad.csv:3: volume 1e+300 is more than 1000 cells"
sed 's|points: nodes.csv|points: missing.csv|' "$tmp/points.yaml" > "$tmp/missing.yaml"
"$bin" check "$tmp/missing.yaml" > "$tmp/missing.log" 2>&1
[[ $? -eq 2 ]] && grep -q "missing.csv: cannot open" "$tmp/missing.log" && echo "ok   refused: a missing file" ||
  { echo "FAIL missing file: $(head -2 "$tmp/missing.log")"; fail=1; }
exit $fail
