#!/usr/bin/env bash
# Strong scaling of distributed runs on this machine, in alternating runs (the machine is noisy):
# the 3D PMB block (216,000 nodes, about 115 bonds per node, 200 steps) on 1 rank x 1 thread,
# 2 ranks x 1 thread and 1 rank x 2 threads, REPEATS times each in turn. Prints the time-stepping
# rate (summary.json's bond_evals_per_s, from the solver's wall time) of each run and the ratios
# of the medians: 2 ranks against 1 rank x 1 thread, and against 1 rank x 2 threads.
#   bash bench/mpi_scaling.sh [REPEATS] [DECK]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
deck=${2:-bench/pmb_block_3d.yaml}
[[ -x build/periadapt ]] || bash scripts/build.sh
build/periadapt --version | grep -q "MPI: yes" || { echo "built without MPI" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
rate() {  # launcher words... -> bond evaluations per second
  "$@" build/periadapt run "$deck" --quiet --set "output.directory=$out/run" > /dev/null
  python3 -c "import json; print(json.load(open('$out/run/summary.json'))['bond_evals_per_s'])"
}
serial=(); threads=(); ranks=()
for ((k = 0; k < repeats; ++k)); do
  serial+=("$(OMP_NUM_THREADS=1 rate env)")
  ranks+=("$(rate mpirun -np 2 -x OMP_NUM_THREADS=1 --bind-to core)")
  threads+=("$(OMP_NUM_THREADS=2 rate env)")
done
python3 - "${serial[*]}" "${ranks[*]}" "${threads[*]}" <<'PY'
import statistics, sys
s, r, t = ([float(v) for v in a.split()] for a in sys.argv[1:4])
for name, v in (("1 rank x 1 thread ", s), ("2 ranks x 1 thread", r), ("1 rank x 2 threads", t)):
    print(f"{name}: " + ", ".join(f"{x:.3e}" for x in v) + f"  median {statistics.median(v):.3e}")
m = statistics.median
print(f"2 ranks / 1 rank x 1 thread: {m(r) / m(s):.3f}; 2 ranks / 1 rank x 2 threads: {m(r) / m(t):.3f}")
PY
