#!/usr/bin/env bash
# Throughput of PeriAdapt against LAMMPS (pair_style peri/pmb) on the same 3D PMB block: same
# simple cubic lattice, horizon 3.015 dx, material, initial expansion velocity, time step and
# number of steps. LAMMPS runs on 1 and 2 MPI ranks, PeriAdapt on 1 and 2 OpenMP threads, in this
# one script so that both see the same machine state.
#
# Usage: bench/compare_lammps.sh [STEPS] [N]     (defaults: 50 steps, N = 60 -> 216,000 nodes)
# Env:   SKIP_INSTALL=1 to skip apt-get; REPEATS (default 1) takes the best of several runs.
#
# Metric: bond evaluations per second = bonds x steps / time-stepping time, where bonds is the
# number of family entries (each bond counted once per owning node, as LAMMPS counts partners);
# times exclude setup on both sides (LAMMPS "Loop time", PeriAdapt solver_time_s).
set -euo pipefail
cd "$(dirname "$0")/.."
steps="${1:-50}"
N="${2:-60}"
repeats="${REPEATS:-1}"

if [[ "${SKIP_INSTALL:-0}" != 1 ]]; then
  bash scripts/install-deps.sh
  if ! command -v lmp > /dev/null || ! command -v mpirun > /dev/null || ! command -v python3 > /dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends lammps openmpi-bin python3
  fi
fi
[[ -x build/periadapt ]] || bash scripts/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

work=$(mktemp -d /tmp/pa-vs-lammps.XXXXXX)
dx=5.0e-4
# Same lattice as the LAMMPS deck: nodes at i*dx, i = 0..N-1, cell-centred body box.
lo=$(python3 -c "print(-0.5*$dx)")
hi=$(python3 -c "print(($N-0.5)*$dx)")
xc=$(python3 -c "print(0.5*($N-1)*$dx)")
sed -e "s/min: \[[^]]*\], max: \[[^]]*\]/min: [$lo, $lo, $lo], max: [$hi, $hi, $hi]/" \
    -e "s/(\([xyz]\)-0.01475)/(\1-$xc)/g" \
    -e "s/steps: 200/steps: $steps/" \
    -e "s#directory: .*#directory: $work/pa#" bench/pmb_block_3d.yaml > "$work/block.yaml"

best() { sort -g | head -1; }

run_lammps() {  # $1 = ranks; prints "loop_seconds atoms"
  local np=$1 t atoms line
  for ((r = 0; r < repeats; ++r)); do
    mpirun -np "$np" lmp -in bench/lammps_pmb_block.in -var N "$N" -var steps "$steps" \
      -log "$work/lammps_np$np.log" -screen none > /dev/null
    line=$(grep "^Loop time" "$work/lammps_np$np.log")
    t=$(awk '{print $4}' <<< "$line")
    atoms=$(awk '{print $(NF-1)}' <<< "$line")
    echo "$t $atoms"
  done | sort -g | head -1
}

run_periadapt() {  # $1 = threads; prints "solver_seconds nodes bonds model_bytes peak_rss build_steps"
  local nt=$1
  for ((r = 0; r < repeats; ++r)); do
    ./build/periadapt run "$work/block.yaml" --out "$work/pa$nt" --threads "$nt" --quiet > /dev/null
    python3 - "$work/pa$nt/summary.json" << 'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
m = d["memory"]
print(d["solver_time_s"], d["nodes"]["initial"], d["bonds"], m["model_bytes"], m["peak_rss_bytes"],
      d["family_build_in_steps"])
EOF
  done | sort -g | head -1
}

echo "3D PMB block: N = $N ($((N * N * N)) nodes), $steps steps, best of $repeats"
read -r l1 atoms1 < <(run_lammps 1)
read -r l2 atoms2 < <(run_lammps 2)
read -r p1 nodes bonds model_bytes rss build_steps < <(run_periadapt 1)
read -r p2 _ _ _ rss2 _ < <(run_periadapt 2)
if [[ "$atoms1" != "$nodes" || "$atoms2" != "$nodes" ]]; then
  echo "lattices differ: LAMMPS $atoms1/$atoms2 atoms, PeriAdapt $nodes nodes" >&2
  exit 1
fi
python3 - "$steps" "$bonds" "$nodes" "$l1" "$l2" "$p1" "$p2" "$model_bytes" "$rss" "$rss2" "$build_steps" << 'EOF'
import sys
steps, bonds, nodes = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
l1, l2, p1, p2 = map(float, sys.argv[4:8])
model, rss, rss2, build = float(sys.argv[8]), float(sys.argv[9]), float(sys.argv[10]), float(sys.argv[11])
ev = bonds * steps
print(f"bonds (family entries)       {bonds:,}  ({bonds / nodes:.1f} per node)")
print(f"{'':28s} {'LAMMPS':>12s} {'PeriAdapt':>12s} {'ratio':>7s}")
for label, l, p in (("1 rank / 1 thread", l1, p1), ("2 ranks / 2 threads", l2, p2)):
    print(f"{label:28s} {ev / l:12.3e} {ev / p:12.3e} {l / p:7.2f}   bond evals/s")
budget = 16 * bonds + 256 * nodes
print(f"PeriAdapt model memory       {model / 1e6:.1f} MB = {model / bonds:.2f} B/bond incl. nodes "
      f"(budget 16 B/bond + 256 B/node = {budget / 1e6:.1f} MB)")
print(f"PeriAdapt peak RSS           {rss / 1e6:.1f} MB (1 thread), {rss2 / 1e6:.1f} MB (2 threads), "
      f"incl. program and libraries")
print(f"family build                 {build:.1f} explicit steps")
EOF
rm -rf "$work"
