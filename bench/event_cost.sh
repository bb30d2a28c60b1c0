#!/usr/bin/env bash
# What refinement events cost against an earlier revision, in alternating runs (the machine is
# noisy): builds REV in a scratch folder (as compare_revisions.sh does), then runs REV's and this
# tree's binaries one after the other on each adaptive deck, REPEATS times each, and prints the
# smallest whole-run wall time and the smallest events' time (summary.json's refinement_wall_s)
# of each, their ratios (this tree over REV) and the event counts. Defaults: the AGRS suite's
# four LPS decks, 3 repeats, one thread
# (THREADS), output.history_every=20 (SET replaces it: LPS refreshes every row at a step whose
# energy densities are asked for).
#   bash bench/event_cost.sh REV [REPEATS] [DECK...]
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bench/event_cost.sh REV [REPEATS] [DECK...]}
shift
repeats=3
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then repeats=$1; shift; fi
decks=("$@")
((${#decks[@]})) || decks=(bench/agrs/*_lps.yaml)
[[ -x build/periadapt ]] || bash scripts/build.sh
old_bin=$(bash bench/revision_binary.sh "$rev")
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
sets=()
for s in ${SET:-output.history_every=20}; do sets+=(--set "$s"); done
measure() {  # binary deck -> "wall events_wall events"
  OMP_NUM_THREADS=${THREADS:-1} "$1" run "$2" --quiet --set "output.directory=$out/run" "${sets[@]}" \
    > /dev/null
  python3 -c "import json; j = json.load(open('$out/run/summary.json')); a = j['adapt']; print(j['wall_time_s'], a['refinement_wall_s'], a['events'])"
}
for deck in "${decks[@]}"; do
  old=(); new=()
  for ((k = 0; k < repeats; ++k)); do
    old+=("$(measure "$old_bin" "$deck")")
    new+=("$(measure build/periadapt "$deck")")
  done
  python3 - "$(basename "$deck" .yaml)" "$rev" "$(printf '%s;' "${old[@]}")" "$(printf '%s;' "${new[@]}")" <<'PY'
import sys
name, rev = sys.argv[1], sys.argv[2]
runs = [[[float(v) for v in r.split()] for r in a.split(";") if r] for a in sys.argv[3:5]]
(o, n) = runs
wo, wn = min(r[0] for r in o), min(r[0] for r in n)
eo, en = min(r[1] for r in o), min(r[1] for r in n)
print(f"{name}: wall {wo:.3f} s ({rev}) -> {wn:.3f} s, ratio {wn / wo:.3f}; "
      f"events {eo:.3f} -> {en:.3f} s, ratio {en / eo:.3f} "
      f"({int(o[0][2])} / {int(n[0][2])} events)")
PY
done
