#!/usr/bin/env bash
# Medium validation (CI): the adaptive crack-branching example of thesis 6.1 end to end. Checks
# facts that do not depend on the branching dynamics we do not yet reproduce (see the closing
# notes): the run completes, AGRS refines (4,000 coarse nodes grow, level 1 reached, momentum
# conserved by every event to 1e-9), the pre-crack starts to run between 5 and 7 us (published
# 6.00 us; the tensile wave needs 3.5 us to reach the crack line), and ParaView, PNG and CSV
# outputs exist.
set -u
bin="$1"; deck="$2"; out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" run "$deck" --out "$out" --quiet > "$out/log.txt" 2>&1 || { cat "$out/log.txt"; echo "FAIL: run"; exit 1; }
s="$out/summary.json"
num() { grep -m1 "\"$1\"" "$s" | sed -E 's/.*: *([-0-9.eE+]+).*/\1/'; }
ti=$(num initiation_time_s); final=$(num final); added=$(num nodes_added); lvl=$(num finest_level)
fail=0
awk -v t="$ti" 'BEGIN { exit !(t >= 5e-6 && t <= 7e-6) }' || { echo "FAIL: initiation $ti s not in [5, 7] us"; fail=1; }
awk -v n="$final" 'BEGIN { exit !(n > 4000) }' || { echo "FAIL: final active nodes $final"; fail=1; }
[[ "$lvl" == 1 ]] || { echo "FAIL: finest level $lvl"; fail=1; }
# Column 9 of refinement.csv: relative change of linear momentum in the event.
awk -F, 'NR > 1 && $9 + 0 > 1e-9 { bad = 1 } END { exit bad }' "$out/refinement.csv" || { echo "FAIL: momentum not conserved by a refinement event"; fail=1; }
for f in snapshot.pvd history.csv refinement.csv damage_0050.000us.png; do
  [[ -s "$out/$f" ]] || { echo "FAIL: missing $f"; fail=1; }
done
echo "initiation $ti s, nodes 4000 -> $final (+$added), finest level $lvl"
exit $fail
