#!/usr/bin/env bash
# Output failures stop the run with exit code 4 and a message naming the file; what was written
# before stays valid. Cases: a full filesystem (a 3 MB tmpfs; skipped with a message where it
# cannot be mounted), a folder where summary.json should go, an output folder that cannot be
# created, a second run into a folder another run holds, and output names that are not regular
# files (a FIFO and a device keep being what they are; a symbolic link is written through).
set -u
bin="$1"; examples="$2"; vtu_py="$3"; fail=0
tmp=$(mktemp -d)
cleanup() { mountpoint -q "$tmp/full" 2>/dev/null && umount "$tmp/full"; rm -rf "$tmp"; }
trap cleanup EXIT
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fail=1; }

# 1. Full filesystem: the adaptive example needs about 6 MB of snapshots.
mkdir -p "$tmp/full"
if mount -t tmpfs -o size=3m tmpfs "$tmp/full" 2>/dev/null; then
  out=$("$bin" run "$examples/crack_branching_2d_adaptive.yaml" --out "$tmp/full/run" --quiet 2>&1); rc=$?
  [[ $rc -eq 4 && "$out" == *"cannot write $tmp/full/run/"*"No space left on device"* ]] \
    && ok "full disk: $out" || bad "full disk: exit $rc: $out"
  # The collection lists only complete snapshots, and each reads back whole.
  python3 - "$tmp/full/run" "$vtu_py" <<'PY' && ok "full disk: snapshot.pvd and its VTUs read back" || bad "full disk: a kept output is corrupt"
import os, re, sys
sys.path.insert(0, os.path.dirname(sys.argv[2]))
from vtu import read_vtu
d = sys.argv[1]
files = re.findall(r'file="([^"]+)"', open(os.path.join(d, 'snapshot.pvd')).read())
assert files, 'no snapshot listed'
for f in files:
    fields = read_vtu(os.path.join(d, f))
    n = len(fields['Points'])
    assert n > 0 and all(len(v) == n for v in fields.values()), f
assert not any(n.endswith('.tmp') for n in os.listdir(d)), 'a temporary file was left'
PY
  grep -q '"status": "output_failed"' "$tmp/full/run/summary.json" 2>/dev/null \
    && ok "full disk: summary.json says output_failed" \
    || echo "note full disk: no room left even for the failure summary"
  umount "$tmp/full"
else
  echo "skip full disk: cannot mount a tmpfs here (needs root and mount rights)"
fi

# 2. A folder in the place of summary.json: the rename onto it fails at the end of the run.
mkdir -p "$tmp/dir/summary.json"
out=$("$bin" run "$examples/crack_branching_2d_adaptive.yaml" --out "$tmp/dir" --quiet 2>&1); rc=$?
[[ $rc -eq 4 && "$out" == *"cannot write $tmp/dir/summary.json"* ]] \
  && ok "summary.json is a folder: $out" || bad "summary.json is a folder: exit $rc: $out"
[[ -f "$tmp/dir/history.csv" && -f "$tmp/dir/snapshot.pvd" ]] && ok "the other outputs are complete" \
  || bad "history.csv or snapshot.pvd missing"

# 3. An output folder that cannot be created (below a regular file).
touch "$tmp/file"
out=$("$bin" run "$examples/crack_branching_2d_adaptive.yaml" --out "$tmp/file/run" --quiet 2>&1); rc=$?
[[ $rc -eq 4 && "$out" == *"cannot create the output folder $tmp/file/run"* ]] \
  && ok "uncreatable folder: $out" || bad "uncreatable folder: exit $rc: $out"

# 4. Another run holds the folder.
mkdir -p "$tmp/held"
flock "$tmp/held/.periadapt.lock" sleep 30 &
holder=$!
for _ in $(seq 50); do flock -n "$tmp/held/.periadapt.lock" true 2>/dev/null || break; sleep 0.1; done
out=$("$bin" run "$examples/crack_branching_2d_adaptive.yaml" --out "$tmp/held" --quiet 2>&1); rc=$?
kill "$holder" 2>/dev/null; wait "$holder" 2>/dev/null
[[ $rc -eq 4 && "$out" == *"another run is writing into $tmp/held"* ]] \
  && ok "held folder: $out" || bad "held folder: exit $rc: $out"
[[ ! -e "$tmp/held/history.csv" ]] && ok "held folder: nothing written" || bad "held folder: files written"
# 5. Names that are not regular files: a rename would replace them (as root, /dev/null itself).
mkdir -p "$tmp/special"
mkfifo "$tmp/special/fifo"
echo "old" > "$tmp/special/target.csv"
ln -s target.csv "$tmp/special/link.csv"
out=$("$bin" check "$examples/crack_branching_2d.yaml" --write-nodes "$tmp/special/fifo" 2>&1); rc=$?
[[ $rc -eq 4 && "$out" == *"is not a regular file"* && -p "$tmp/special/fifo" ]] \
  && ok "FIFO kept: $out" || bad "FIFO: exit $rc: $out"
if mknod "$tmp/special/null" c 1 3 2>/dev/null; then
  out=$("$bin" check "$examples/crack_branching_2d.yaml" --write-nodes "$tmp/special/null" 2>&1); rc=$?
  [[ $rc -eq 4 && -c "$tmp/special/null" ]] && ok "device kept: $out" || bad "device: exit $rc: $out"
else
  echo "skip device node (mknod not permitted)"
fi
"$bin" check "$examples/crack_branching_2d.yaml" --write-nodes "$tmp/special/link.csv" > /dev/null 2>&1; rc=$?
[[ $rc -eq 0 && -L "$tmp/special/link.csv" && "$(head -1 "$tmp/special/target.csv")" == x,y,volume* ]] \
  && ok "link written through" || bad "link: exit $rc, link kept: $([[ -L $tmp/special/link.csv ]] && echo yes || echo no)"
exit $fail
