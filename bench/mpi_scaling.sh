#!/usr/bin/env bash
# Strong scaling of distributed runs on this machine, in alternating runs (the machine is noisy):
# the 3D PMB block (216,000 nodes, about 115 bonds per node, 200 steps) on 1 rank x 1 thread,
# 2 ranks x 1 thread (each rank integrating its own region, and every rank integrating every node:
# solver.owned_integration false) and 1 rank x 2 threads, REPEATS times each in turn. Prints the
# time-stepping rate (summary.json's bond_evals_per_s, from the solver's wall time) of each run and
# the ratios of the medians: 2 ranks against 1 rank x 1 thread, and against 1 rank x 2 threads.
# Also the median of each round's own ratios: the runs of one round follow each other within a
# minute, so a slow spell of the machine that spans a round cancels in its ratio.
#   [PERIADAPT=path/to/periadapt] bash bench/mpi_scaling.sh [REPEATS] [DECK]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
deck=${2:-bench/pmb_block_3d.yaml}
bin=${PERIADAPT:-build/periadapt}
[[ -x $bin ]] || bash scripts/build.sh
"$bin" --version | grep -q "MPI: yes" || { echo "built without MPI" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
rate() {  # owned_integration launcher words... -> bond evaluations per second
  local owned=$1; shift
  "$@" "$bin" run "$deck" --quiet --set "output.directory=$out/run" \
    --set "solver.owned_integration=$owned" > /dev/null
  python3 -c "import json; print(json.load(open('$out/run/summary.json'))['bond_evals_per_s'])"
}
serial=(); threads=(); ranks=(); replicated=()
for ((k = 0; k < repeats; ++k)); do
  serial+=("$(OMP_NUM_THREADS=1 rate true env)")
  ranks+=("$(rate true mpirun -np 2 -x OMP_NUM_THREADS=1 --bind-to core)")
  threads+=("$(OMP_NUM_THREADS=2 rate true env)")
  replicated+=("$(rate false mpirun -np 2 -x OMP_NUM_THREADS=1 --bind-to core)")
done
python3 - "${serial[*]}" "${ranks[*]}" "${threads[*]}" "${replicated[*]}" <<'PY'
import statistics, sys
s, r, t, w = ([float(v) for v in a.split()] for a in sys.argv[1:5])
for name, v in (("1 rank x 1 thread ", s), ("2 ranks x 1 thread", r), ("1 rank x 2 threads", t),
                ("2 ranks, replicated", w)):
    print(f"{name}: " + ", ".join(f"{x:.3e}" for x in v) + f"  median {statistics.median(v):.3e}")
m = statistics.median
print(f"2 ranks / 1 rank x 1 thread: {m(r) / m(s):.3f}; 2 ranks / 1 rank x 2 threads: {m(r) / m(t):.3f}")
print(f"replicated integration: {m(w) / m(s):.3f} and {m(w) / m(t):.3f}")
rs = [a / b for a, b in zip(r, s)]
rt = [a / b for a, b in zip(r, t)]
print("per round, 2 ranks / 1 rank x 1 thread: " + ", ".join(f"{x:.3f}" for x in rs) + f"  median {m(rs):.3f}")
print("per round, 2 ranks / 1 rank x 2 threads: " + ", ".join(f"{x:.3f}" for x in rt) + f"  median {m(rt):.3f}")
PY
