#!/usr/bin/env bash
# periadapt sweep: every combination runs in its own folder; sweep.csv has one row per run; a run
# of the sweep equals the same deck run alone with the same --set; a bad value is refused (exit 2)
# before any run starts.
set -u
bin="$1"; deck="$2"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ok() { echo "ok   $*"; }
bad() { echo "FAIL $*"; fail=1; }
"$bin" sweep "$deck" --out "$tmp/sw" --quiet --set material.fracture_energy=100,135 \
  --set 'loads.0.value=[0, 1.0e7],[0, 1.4e7]' --set solver.end_time=1.0e-5 > "$tmp/log" 2>&1 ||
  bad "sweep: $(cat "$tmp/log")"
rows=$(($(wc -l < "$tmp/sw/sweep.csv") - 1))
[[ $rows -eq 4 ]] && ok "sweep.csv has 4 runs" || bad "sweep.csv has $rows runs"
grep -q '^run_0001,100,"\[0, 1.4e7\]",1.0e-5,completed,' "$tmp/sw/sweep.csv" && ok "run_0001: G0 100, the second load" ||
  bad "run_0001 row: $(sed -n 3p "$tmp/sw/sweep.csv")"
"$bin" run "$deck" --out "$tmp/alone" --quiet --set material.fracture_energy=100 \
  --set 'loads.0.value=[0, 1.4e7]' --set solver.end_time=1.0e-5 > /dev/null 2>&1
cmp <(cut -d, -f1-15 "$tmp/alone/history.csv") <(cut -d, -f1-15 "$tmp/sw/run_0001/history.csv") &&
  ok "run_0001 equals the same run alone" || bad "run_0001 differs from the same run alone"
"$bin" sweep "$deck" --out "$tmp/bad" --quiet --set material.fracture_energy=100,-5 > "$tmp/log" 2>&1; rc=$?
[[ $rc -eq 2 && ! -e $tmp/bad/run_0000 ]] && grep -q "material.fracture_energy" "$tmp/log" &&
  ok "a bad value: exit 2 before any run" || bad "a bad value: exit $rc: $(cat "$tmp/log")"
# The same key swept twice (its rows were labelled with the first --set's values) and a swept
# output folder (each run has its own) are refused before any run.
"$bin" sweep "$deck" --out "$tmp/twice" --quiet --set solver.steps=10,20 --set solver.steps=30 > "$tmp/log" 2>&1; rc=$?
[[ $rc -eq 2 && ! -e $tmp/twice/run_0000 ]] && grep -q "swept twice" "$tmp/log" &&
  ok "a key swept twice: exit 2" || bad "a key swept twice: exit $rc: $(cat "$tmp/log")"
"$bin" sweep "$deck" --out "$tmp/dirs" --quiet --set output.directory=a,b > "$tmp/log" 2>&1; rc=$?
[[ $rc -eq 2 && ! -e $tmp/dirs/run_0000 ]] && grep -q "cannot be swept" "$tmp/log" &&
  ok "output.directory swept: exit 2" || bad "output.directory swept: exit $rc: $(cat "$tmp/log")"
exit $fail
