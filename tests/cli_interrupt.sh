#!/usr/bin/env bash
# SIGTERM and SIGINT stop a run after its current step: exit code 128 + signal, history.csv
# complete to its last row, the snapshots so far readable, summary.json with status interrupted.
set -u
bin="$1"; deck="$2"; vtu_py="$3"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for sig in TERM INT; do
  out="$tmp/$sig"
  "$bin" run "$deck" --out "$out" --quiet > "$tmp/$sig.log" 2>&1 &
  pid=$!
  for _ in $(seq 200); do [[ -s "$out/history.csv.part" ]] && break; sleep 0.05; done
  sleep 0.2
  kill -s "$sig" "$pid"
  wait "$pid"; rc=$?
  want=$((128 + $(kill -l "$sig")))
  [[ $rc -eq $want ]] && echo "ok   SIG$sig: exit $rc" || { echo "FAIL SIG$sig: exit $rc (want $want): $(cat "$tmp/$sig.log")"; fail=1; }
  python3 - "$out" "$vtu_py" <<'PY' && echo "ok   SIG$sig: summary, history and snapshots" || { echo "FAIL SIG$sig: outputs"; fail=1; }
import csv, json, os, re, sys
sys.path.insert(0, os.path.dirname(sys.argv[2]))
from vtu import read_vtu
d = sys.argv[1]
s = json.load(open(os.path.join(d, 'summary.json')))
assert s['status'] == 'interrupted' and s['steps_done'] > 0, s['status']
rows = list(csv.reader(open(os.path.join(d, 'history.csv'))))
assert len(rows) > 2 and all(len(r) == len(rows[0]) for r in rows), 'history cut'
assert int(rows[-1][0]) == s['steps_done'], (rows[-1][0], s['steps_done'])
for f in re.findall(r'file="([^"]+)"', open(os.path.join(d, 'snapshot.pvd')).read()):
    assert len(read_vtu(os.path.join(d, f))['Points']) > 0
PY
done
exit $fail
