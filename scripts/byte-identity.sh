#!/usr/bin/env bash
# Shows that a restructuring changed no result: builds two revisions, runs every example deck and
# every study with each, and compares their outputs byte for byte:
#   history.csv and refinement.csv without their wall-time columns, summary.json without its
#   timings, paths and memory figures, every study CSV, crack_speed.csv and displacement.csv.
# A developer script (issue 22's acceptance), not part of CI: about 10-20 minutes per revision
# on 2 cores (--quick leaves out the studies and the decks that run over a minute).
#   bash scripts/byte-identity.sh [--quick] [--work DIR] BEFORE [AFTER]
# BEFORE, AFTER: git revisions; AFTER defaults to the working tree (tracked and untracked files).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
quick=0
work=${TMPDIR:-/tmp}/periadapt-identity
revs=()
while (($#)); do
  case $1 in
    --quick) quick=1; shift ;;
    --work) work=$2; shift 2 ;;
    -*) echo "usage: $0 [--quick] [--work DIR] BEFORE [AFTER]" >&2; exit 2 ;;
    *) revs+=("$1"); shift ;;
  esac
done
((${#revs[@]} >= 1 && ${#revs[@]} <= 2)) || { echo "usage: $0 [--quick] [--work DIR] BEFORE [AFTER]" >&2; exit 2; }
before=${revs[0]}; after=${revs[1]:-WORKTREE}
slow="three_point_bending_lps crack_branching_3d_adaptive pdro_disk_2d"
mkdir -p "$work"

tree() {  # revision -> its source tree under $work/<name>/src
  local rev=$1 dir=$work/$2/src
  rm -rf "$dir"; mkdir -p "$dir"
  if [[ $rev == WORKTREE ]]; then
    git ls-files -co --exclude-standard -z | tar -cf - --null -T - | tar -xf - -C "$dir"
  else
    git archive "$rev" | tar -xf - -C "$dir"
  fi
}
outputs() {  # name: build and run everything into $work/<name>/out
  local name=$1 src=$work/$1/src out=$work/$1/out
  cmake -S "$src" -B "$work/$name/build" -DCMAKE_BUILD_TYPE=Release -DPERIADAPT_BUILD_TESTS=OFF \
    -DPERIADAPT_BUILD_BENCH=OFF > /dev/null
  cmake --build "$work/$name/build" -j"$(nproc)" > "$work/$name/build.log" 2>&1 ||
    { tail -20 "$work/$name/build.log"; exit 1; }
  local bin=$work/$name/build/periadapt
  rm -rf "$out"; mkdir -p "$out"
  for deck in "$src"/examples/*.yaml; do
    local d; d=$(basename "$deck" .yaml)
    ((quick)) && [[ " $slow " == *" $d "* ]] && continue
    (cd "$src" && OMP_NUM_THREADS=2 "$bin" run "$deck" --quiet --set "output.directory=$out/$d") \
      > "$out/$d.log" 2>&1 || echo "$name: $d exited $?" >> "$out/exits.txt"
  done
  if ((!quick)); then
    for study in $("$bin" study --help | sed -n 's/.*TEXT:{\([^}]*\)}.*/\1/p' | tr , ' '); do
      OMP_NUM_THREADS=2 "$bin" study "$study" --out "$out/study-$study" > "$out/study-$study.log" 2>&1 ||
        echo "$name: study $study exited $?" >> "$out/exits.txt"
    done
  fi
}

echo "revisions: before $before, after $after (work folder $work)"
tree "$before" before
tree "$after" after
for side in before after; do
  echo "building and running $side ..."
  outputs "$side"
done
python3 - "$work/before/out" "$work/after/out" <<'PY'
import csv, io, json, os, re, sys
a, b = sys.argv[1], sys.argv[2]
# Wall-clock measures and paths; everything else (crack times, energies, counts) must agree.
timing = re.compile(r"^(wall_time_s|setup_time_s|solver_time_s|sampling_time_s|"
                    r"snapshot_output_time_s|family_build_time_s|family_build_in_steps|"
                    r"refinement_wall_s|bond_evals_per_s|peak_rss_bytes|rss_end_bytes|outputs|deck|"
                    r"assemble_time_s|solve_time_s|event_wall_s)$")

def table(path):
    rows = list(csv.reader(open(path)))
    if not rows: return rows
    keep = [i for i, h in enumerate(rows[0]) if not re.search(r"wall", h)]
    return [[r[i] for i in keep if i < len(r)] for r in rows]

def clean(x):
    if isinstance(x, dict):
        return {k: clean(v) for k, v in x.items() if not timing.search(k)}
    if isinstance(x, list):
        return [clean(v) for v in x]
    return x

files = same = 0
differ = []
for dirpath, _, names in os.walk(a):
    for n in sorted(names):
        pa = os.path.join(dirpath, n)
        rel = os.path.relpath(pa, a)
        pb = os.path.join(b, rel)
        if n.endswith(".csv"):
            ok = os.path.exists(pb) and table(pa) == table(pb)
        elif n == "summary.json":
            ok = os.path.exists(pb) and clean(json.load(open(pa))) == clean(json.load(open(pb)))
        elif n == "exits.txt":
            ok = os.path.exists(pb) and open(pa).read().replace("before", "") == open(pb).read().replace("after", "")
        else:
            continue
        files += 1
        same += ok
        if not ok: differ.append(rel)
for dirpath, _, names in os.walk(b):
    for n in names:
        rel = os.path.relpath(os.path.join(dirpath, n), b)
        if (n.endswith(".csv") or n == "summary.json") and not os.path.exists(os.path.join(a, rel)):
            differ.append(rel + " (after only)")
print(f"{same} of {files} compared files identical")
for d in differ: print("DIFFERS", d)
sys.exit(1 if differ else 0)
PY
