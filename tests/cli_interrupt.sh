#!/usr/bin/env bash
# SIGTERM and SIGINT stop a run after its current step: exit code 128 + signal, history.csv
# complete to its last row, the snapshots so far readable, summary.json with status interrupted.
# A dynamic-relaxation run stops in its current load step and keeps the converged ones.
set -u
bin="$1"; deck="$2"; vtu_py="$3"; relax_deck="$4"; fail=0
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
out="$tmp/relax"
"$bin" run "$relax_deck" --out "$out" --quiet > "$tmp/relax.log" 2>&1 &
pid=$!
for _ in $(seq 1200); do [[ $(wc -l < "$out/history.csv.part" 2>/dev/null || echo 0) -ge 3 ]] && break; sleep 0.05; done
kill -s TERM "$pid"
wait "$pid"; rc=$?
[[ $rc -eq 143 ]] && echo "ok   relaxation SIGTERM: exit $rc" || { echo "FAIL relaxation SIGTERM: exit $rc (want 143): $(cat "$tmp/relax.log")"; fail=1; }
python3 - "$out" <<'PY' && echo "ok   relaxation: summary and history up to the last converged load step" || { echo "FAIL relaxation: outputs"; fail=1; }
import csv, json, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, 'summary.json')))
assert s['status'] == 'interrupted', s['status']
rows = list(csv.reader(open(os.path.join(d, 'history.csv'))))
n = s['load_steps_converged']
assert 2 <= n < 30 and len(rows) == n + 1, (n, len(rows))
assert [int(r[0]) for r in rows[1:]] == list(range(1, n + 1))
PY
exit $fail
