#!/usr/bin/env bash
# Memory per rank of distributed runs: the 3D PMB block (216,000 nodes, about 115 bonds per node)
# for 20 steps on 1 rank, and on 2 and 4 ranks (1 thread each, oversubscribed past the cores)
# with each rank holding its own bond rows (the default without refinement events) and with
# every rank holding the whole model (solver.owned_integration false); then held rows writing a
# checkpoint at step 10 (each rank its rows' piece), and that checkpoint restarted on as many
# ranks. Prints rank 0's model arrays (summary.json memory.model_bytes), its peak resident memory
# and its resident memory at the end, the largest peak over the ranks, in MB, and the held runs'
# rank-0 peaks over the 1-rank run's. STEPS "deck" runs the deck's own end time (an adaptive
# deck's events), CHECKPOINT_EVERY sets where the checkpoint rows write (and restart from).
#   [PERIADAPT=path/to/periadapt] bash bench/mpi_memory.sh [DECK [STEPS [CHECKPOINT_EVERY]]]
#   e.g. bash bench/mpi_memory.sh bench/crack_branching_3d_adaptive_fine.yaml deck 200
set -euo pipefail
cd "$(dirname "$0")/.."
deck=${1:-bench/pmb_block_3d.yaml}
steps=${2:-20}
every=${3:-10}
length=(--set "solver.steps=$steps")
[[ $steps == deck ]] && length=()
bin=${PERIADAPT:-build/periadapt}
[[ -x $bin ]] || bash scripts/build.sh
"$bin" --version | grep -q "MPI: yes" || { echo "built without MPI" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
row() {  # label owned extra-args launcher words...
  local label=$1 owned=$2 extra=$3; shift 3
  "$@" "$bin" run "$deck" --quiet --set "output.directory=$out/run" "${length[@]}" \
    --set "solver.owned_integration=$owned" $extra > /dev/null
  python3 - "$out/run/summary.json" "$label" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); m = j["memory"]; r = j.get("ranks", {})
held = r.get("bond_rows_rank0")
largest = m.get("peak_rss_largest_rank_bytes", m["peak_rss_bytes"])
print(f"{sys.argv[2]:<22} {m['model_bytes'] / 1e6:9.1f} {m['peak_rss_bytes'] / 1e6:9.1f} "
      f"{m['rss_end_bytes'] / 1e6:9.1f} {largest / 1e6:9.1f}  "
      f"{held if held is not None else j['nodes']['slots']}")
PY
}
echo "run                    model MB   peak MB    end MB  peak any  bond rows (rank 0)"
one=$(OMP_NUM_THREADS=1 row "1 rank" true "" env); echo "$one"
for np in 2 4; do
  mpi=(mpirun -np "$np" -x OMP_NUM_THREADS=1)
  row "$np ranks, held rows" true "" "${mpi[@]}"
  row "$np ranks, whole model" false "" "${mpi[@]}"
  row "$np held, checkpoint" true "--set output.checkpoint_every=$every" "${mpi[@]}"
  row "$np held, restarted" true "--restart $out/run" "${mpi[@]}"
done | tee "$out/rows"
python3 - "$one" "$out/rows" <<'PY'
import sys
base = float(sys.argv[1][22:].split()[1])
for line in open(sys.argv[2]):
    if "held" in line:
        print(f"{line[:22].strip()}: peak {float(line[22:].split()[1]) / base:.3f} of 1 rank's")
PY
