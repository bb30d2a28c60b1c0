#!/usr/bin/env bash
# Named node sets: a region {node_set: {points: FILE, block: N}} is the cells of the nodes of
# block N of a point file (its optional block column). The adaptive crack-branching example with
# its load strips and no-fail strips given as node sets (blocks 1 and 2 of its own lattice,
# written by `check --write-nodes`) runs bit for bit as with its boxes: the same history (less
# wall times), refinement log, VTU snapshots and broken bonds, children included (a node set
# holds its nodes' cells, so children of its nodes belong to it). Refused with exit 2: a block
# no point has, a file without a block column, a negative block id.
set -u
bin="$1"; example="$2"; fail=0
tmp=${KEEP:-$(mktemp -d)}; [[ -n ${KEEP:-} ]] || trap 'rm -rf "$tmp"' EXIT
cp "$example" "$tmp/box.yaml"
"$bin" check "$tmp/box.yaml" --write-nodes "$tmp/lattice.csv" > /dev/null || { echo "FAIL check --write-nodes"; fail=1; }
python3 - "$tmp" <<'PY' || fail=1
import re, sys
tmp = sys.argv[1]
rows = open(f"{tmp}/lattice.csv").read().split("\n")
out = [rows[0] + ",block"]
for r in rows[1:]:
    if not r.strip():
        continue
    y = float(r.split(",")[1])
    out.append(r + "," + ("1" if y > 0.039 else "2" if y < 0.001 else "0"))
open(f"{tmp}/sets.csv", "w").write("\n".join(out) + "\n")
s = open(f"{tmp}/box.yaml").read()
# A traction on a region other than a box names its layer depth. Both decks give it (a box's
# default, the strip's volume over its face, differs from 1 mm in the last bit).
s, k = re.subn(r"(\n    value: \[0\.0, -?14\.0e6\])", r"\1\n    layer: 1.0e-3", s)
assert k == 2, "expected the example's two traction values"
open(f"{tmp}/box.yaml", "w").write(s)
top = "box: {min: [0.0, 0.039], max: [0.1, 0.04]}"
bottom = "box: {min: [0.0, 0.0], max: [0.1, 0.001]}"
n = s.count(top) + s.count(bottom)
assert n == 4, f"expected the example's two load and two no-fail boxes, found {n}"
s = s.replace(top, "node_set: {points: sets.csv, block: 1}")
s = s.replace(bottom, "node_set: {points: sets.csv, block: 2}")
open(f"{tmp}/sets.yaml", "w").write(s)
PY
grep -n "node_set" "$tmp/sets.yaml" | head -2
"$bin" run "$tmp/box.yaml" --out "$tmp/box" --quiet > /dev/null 2>&1 || { echo "FAIL box run"; fail=1; }
"$bin" run "$tmp/sets.yaml" --out "$tmp/sets" --quiet > "$tmp/sets.log" 2>&1 || { echo "FAIL node-set run"; cat "$tmp/sets.log"; fail=1; }
python3 - "$tmp" <<'PY' || fail=1
import csv, filecmp, glob, json, os, sys
tmp = sys.argv[1]
def rows(d, f):
    return [",".join(l.rstrip("\n").split(",")[:-1]) for l in open(f"{tmp}/{d}/{f}")]
same_hist = rows("box", "history.csv") == rows("sets", "history.csv")
same_ref = rows("box", "refinement.csv") == rows("sets", "refinement.csv")
vtus = sorted(glob.glob(f"{tmp}/box/snapshot_*.vtu"))
same_vtu = len(vtus) > 1 and all(
    filecmp.cmp(v, f"{tmp}/sets/{os.path.basename(v)}", shallow=False) for v in vtus)
ja, jb = (json.load(open(f"{tmp}/{d}/summary.json")) for d in ("box", "sets"))
same = ja["broken_bonds"] == jb["broken_bonds"] > 0 and ja["nodes"] == jb["nodes"]
events = ja["adapt"]["events"]
for ok, what in ((same_hist, "history.csv"), (same_ref, f"refinement.csv ({events} events)"),
                 (same_vtu, f"{len(vtus)} VTU snapshots"),
                 (same, f"broken bonds {ja['broken_bonds']}, final nodes {ja['nodes']['final']}")):
    print(("ok   " if ok else "FAIL ") + "node sets = boxes, bit for bit: " + what)
sys.exit(0 if same_hist and same_ref and same_vtu and same and events > 0 else 1)
PY
refused() {  # name deck-edit message
  sed "$2" "$tmp/sets.yaml" > "$tmp/bad.yaml"
  "$bin" check "$tmp/bad.yaml" > "$tmp/bad.log" 2>&1
  local rc=$?
  if [[ $rc -eq 2 ]] && grep -q -- "$3" "$tmp/bad.log"; then echo "ok   refused: $1"
  else echo "FAIL $1: exit $rc, $(head -2 "$tmp/bad.log")"; fail=1; fi
}
refused "a block no point has" 's/block: 2}/block: 7}/' "is in block 7"
refused "a negative block" 's/block: 2}/block: -1}/' "block id is >= 0"
refused "a file without a block column" 's/points: sets.csv, block: 1/points: lattice.csv, block: 1/' "no block column"
exit $fail
