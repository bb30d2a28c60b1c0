#!/usr/bin/env bash
# Throughput of this tree against an earlier revision on the same deck, in alternating runs (the
# machine is noisy): builds REV in a scratch folder, then runs REV's and this tree's binaries one
# after the other, REPEATS times each, and prints the bond evaluations per second of the time
# stepping (summary.json's bond_evals_per_s) with the ratio of the medians.
#   bash bench/compare_revisions.sh REV [DECK] [REPEATS]
# DECK defaults to bench/pmb_block_3d.yaml (the LAMMPS comparison's 3D PMB block, 216,000
# nodes, 200 steps); REPEATS to 5. Both binaries use the threads OMP_NUM_THREADS gives, and run
# under LAUNCH when set (e.g. LAUNCH="mpirun -np 2 -x OMP_NUM_THREADS=1 --bind-to core"); SET adds
# --set overrides (e.g. SET="output.history_every=1"). METRIC=run counts the whole run loop
# (time stepping, syncs and outputs: bond evaluations over the wall time less the set-up).
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bench/compare_revisions.sh REV [DECK] [REPEATS]}
deck=${2:-bench/pmb_block_3d.yaml}
repeats=${3:-5}
[[ -x build/periadapt ]] || bash scripts/build.sh
old_bin=$(bash bench/revision_binary.sh "$rev")
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
rate() {  # binary -> bond evaluations per second
  local sets=()
  for s in ${SET:-}; do sets+=(--set "$s"); done
  ${LAUNCH:-} "$1" run "$deck" --quiet --set "output.directory=$out/run" "${sets[@]}" > /dev/null
  python3 -c "import json; j = json.load(open('$out/run/summary.json')); print(j['bond_evals_per_s'] if '${METRIC:-}' != 'run' else j['bond_evaluations'] / (j['wall_time_s'] - j['setup_time_s']))"
}
old=(); new=()
for ((k = 0; k < repeats; ++k)); do
  old+=("$(rate "$old_bin")")
  new+=("$(rate build/periadapt)")
done
python3 - "$rev" "${old[*]}" "${new[*]}" <<'PY'
import statistics, sys
rev, old, new = sys.argv[1], [float(x) for x in sys.argv[2].split()], [float(x) for x in sys.argv[3].split()]
mo, mn = statistics.median(old), statistics.median(new)
print(f"{rev}: " + " ".join(f"{x:.3e}" for x in old) + f"  median {mo:.4e} bond evaluations/s")
print(f"this tree: " + " ".join(f"{x:.3e}" for x in new) + f"  median {mn:.4e}")
print(f"ratio this tree / {rev} (medians): {mn / mo:.4f}; best of each: {max(new) / max(old):.4f}")
PY
