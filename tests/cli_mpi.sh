#!/usr/bin/env bash
# Distributed runs (mpirun): each deck on 2 and 3 ranks (1 thread each, oversubscribed where the
# machine has fewer cores) ends exactly where the serial run ends: history.csv and
# refinement.csv but their wall-time columns, every snapshot's nodes with every field bit for bit
# (the ranks' VTU pieces merged; hence the same broken bonds and displacements), summary.json but
# timings, paths and the rank report (the energies and the external work too: each rank adds
# its own nodes into exact sums). Then a
# checkpoint written on 2 ranks (every 100 steps) restarts on 3 and ends as the serial run does
# (with held rows, from bond pieces, which also restart a serial run; a serial checkpoint restarts
# on 2 ranks holding their rows);
# where the ranks integrate their own regions (parallel/ghost_layer.hpp), they did so on some steps,
# and no event that synced only its window left a region node stale;
# an output failure on rank 0 stops every rank with exit code 4, and a diverging run stops every
# rank with the serial run's diagnosis.
# A case's settings may name its rank counts (ranks=3, ranks=2,3): the variants of a deck that
# another case runs on both counts run on 3 alone, the uneven partition. CLI_MPI_RANKS (default
# "2 3") names the rank counts of every case. Skipped (exit 0 with a note) in a build
# without MPI.
set -u
bin="$1"; shift
"$bin" --version 2> /dev/null | grep -q "MPI: yes" || { echo "skip: built without MPI"; exit 0; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Shared-memory transport only, and waiting ranks yield the core (oversubscribed runs).
export OMPI_MCA_btl=self,vader OMPI_MCA_mpi_yield_when_idle=1
# Every refinement event that brings only its window up to date checks that it left no rank's
# region stale (each region node's u and v against its owner's; a run stops if one is).
export PERIADAPT_CHECK_REGIONS=1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0

same() {  # reference folder, folder
  python3 - "$1" "$2" <<'PY'
import json, os, re, struct, sys
a, b = sys.argv[1], sys.argv[2]
def rows(d, f):  # less the wall time and the distributed run's rank_imbalance column
    p = os.path.join(d, f)
    if not os.path.exists(p): return None
    lines = [l.rstrip("\n").split(",")[:-1] for l in open(p)]
    if "rank_imbalance" in lines[0]:
        k = lines[0].index("rank_imbalance")
        lines = [l[:k] + l[k + 1:] for l in lines]
    return lines
# Every column, the external work and the energies included, equals the serial run's to the bit:
# the ranks add exact sums of their own nodes (core/exact_sum.hpp).
for f in ["history.csv", "refinement.csv"]:
    ra, rb = rows(a, f), rows(b, f)
    if ra != rb:
        if ra is None or rb is None or len(ra) != len(rb) or ra[0] != rb[0]: sys.exit(f"{f} differs")
        step = next(x[0] for x, y in zip(ra[1:], rb[1:]) if x != y)
        sys.exit(f"{f} differs at step {step}")
def arrays(path):  # every appended array of a raw VTU: name -> tuple of values
    data = open(path, "rb").read()
    head_end = data.index(b"<AppendedData")
    raw = data.index(b"_", head_end) + 1
    out = {}
    for m in re.finditer(r"<DataArray ([^>]*)/>", data[:head_end].decode()):
        at = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        off = raw + int(at["offset"])
        n = struct.unpack_from("<Q", data, off)[0]
        code, size = {"Float64": ("d", 8), "Int64": ("q", 8), "UInt8": ("B", 1)}[at["type"]]
        vals = struct.unpack_from("<%d%s" % (n // size, code), data, off + 8)
        k = int(at.get("NumberOfComponents", "1"))
        out[at["Name"]] = [vals[i:i + k] for i in range(0, len(vals), k)]
    return out
def points(path):  # node rows (position, then every point field in name order), sorted
    f = arrays(path)
    names = sorted(k for k in f if k not in ("Points", "connectivity", "offsets", "types", "rank"))
    return [tuple(p) + sum((tuple(f[k][i]) for k in names), ()) for i, p in enumerate(f["Points"])], names
def snapshot(d, stem):  # a serial VTU, or the pieces a PVTU names, merged
    if os.path.exists(os.path.join(d, stem + ".vtu")):
        return sorted(points(os.path.join(d, stem + ".vtu"))[0])
    pvtu = open(os.path.join(d, stem + ".pvtu")).read()
    rows = []
    for piece in re.findall(r'<Piece Source="([^"]+)"', pvtu):
        rows += points(os.path.join(d, piece))[0]
    return sorted(rows)
stems = lambda d: sorted(f.rsplit(".", 1)[0] for f in os.listdir(d)
                         if f.endswith(".vtu") and "_r" not in f or f.endswith(".pvtu"))
snaps = stems(a)
if snaps != stems(b): sys.exit("other snapshots")
for f in snaps:
    if snapshot(a, f) != snapshot(b, f): sys.exit(f"{f} differs")
skip = {"wall_time_s", "setup_time_s", "solver_time_s", "sampling_time_s", "snapshot_output_time_s",
        "bond_evals_per_s", "family_build_time_s", "family_build_in_steps", "peak_rss_bytes",
        "refinement_wall_s", "event_wall_s", "outputs", "threads", "ranks", "restarted_from_step",
        "checkpoint", "memory"}
def strip(j):
    if isinstance(j, dict): return {k: strip(v) for k, v in j.items() if k not in skip}
    if isinstance(j, list): return [strip(v) for v in j]
    return j
sa, sb = (strip(json.load(open(os.path.join(d, "summary.json")))) for d in (a, b))
# The damage pictures (rank 0 draws them from what every rank holds), byte for byte.
pngs = lambda d: sorted(f for f in os.listdir(d) if f.startswith("damage_") and f.endswith(".png"))
if pngs(a) != pngs(b): sys.exit(f"other pictures: {pngs(a)} against {pngs(b)}")
for f in pngs(a):
    if open(os.path.join(a, f), "rb").read() != open(os.path.join(b, f), "rb").read():
        sys.exit(f"{f} differs")
if sa != sb: sys.exit("summary.json differs: " + ", ".join(k for k in sa if sa.get(k) != sb.get(k)))
print(f"{len(snaps)} snapshots, {len(pngs(a))} pictures, history and summary equal")
PY
}

while (($#)); do
  name="$1"; deck="$2"; sets="$3"; shift 3
  args=(--quiet --threads 1); ranks=${CLI_MPI_RANKS:-2 3}
  for s in $sets; do
    if [[ $s == ranks=* && -z ${CLI_MPI_RANKS:-} ]]; then ranks=${s#ranks=}; ranks=${ranks//,/ }
    elif [[ $s != ranks=* ]]; then args+=(--set "$s"); fi
  done
  "$bin" run "$deck" --out "$tmp/$name-1" "${args[@]}" > "$tmp/$name-1.log" 2>&1 ||
    { echo "FAIL $name: serial run: $(tail -3 "$tmp/$name-1.log")"; fail=1; continue; }
  for np in $ranks; do
    out="$tmp/$name-$np"
    if ! mpirun -np $np "$bin" run "$deck" --out "$out" "${args[@]}" > "$out.log" 2>&1; then
      echo "FAIL $name: $np ranks: $(tail -3 "$out.log")"; fail=1; continue
    fi
    if r=$(same "$tmp/$name-1" "$out" 2>&1); then echo "ok   $name, $np ranks: $r"
    else echo "FAIL $name, $np ranks: $r"; fail=1; fi
    # Owned integration (explicit runs without contact, impactors, overlay or ghost-force table):
    # the equality above held with ranks that left nodes outside their region stale. Held bond
    # rows (names with "held-" must have them): rank 0 kept fewer rows and bytes than serial.
    if r=$(python3 - "$out" "$tmp/$name-1" "$name" <<'PY'
import json, os, sys
j = json.load(open(os.path.join(sys.argv[1], "summary.json")))
r = j.get("ranks", {})
n = j.get("nodes", {}).get("slots") if isinstance(j.get("nodes"), dict) else None
if r.get("owned_integration"):
    if r["region_steps"] < 1 or r["region_nodes_rank0"] >= n:
        sys.exit(f"owned integration idle: {r}")
    what = (f"{r['region_steps']} of {j['steps']} steps advanced rank 0's region alone "
            f"({r['region_nodes_rank0']} of {n} nodes)")
else:
    what = "whole-model integration"
held = ""
if r.get("held_bond_rows"):
    # Rank 0 kept its own rows (LPS: its region's) and freed the others' bond arrays.
    serial = json.load(open(os.path.join(sys.argv[2], "summary.json")))["memory"]["model_bytes"]
    mine = j["memory"]["model_bytes"]
    if not (r["bond_rows_rank0"] < n and mine < serial):
        sys.exit(f"held bond rows: {r['bond_rows_rank0']} rows, {mine} B against serial {serial} B")
    held = f"; holds {r['bond_rows_rank0']} bond rows, model {mine / serial:.3f} of the serial run's"
elif "held-" in sys.argv[3]:
    sys.exit("held bond rows expected")
print(what + held)
PY
    ); then echo "ok   $name, $np ranks: $r"; else echo "FAIL $name, $np ranks: $r"; fail=1; fi
  done
  # Adaptive rebalancing: refinement events add children on their parent's rank; the imbalance
  # (largest rank's work over the mean, history.csv: bonds per step, a multi-rate row's bonds over
  # its step) stays within the deck's threshold, at least one event repartitioned, and so the
  # bonds each rank's rows evaluated over the run, a count of the work done, are within it too.
  if [[ $name == rebalance-* ]]; then
    first=${ranks%% *}
    if r=$(python3 - "$tmp/$name-$first" <<'PY'
import csv, json, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "history.csv"))))
ranks = json.load(open(os.path.join(d, "summary.json")))["ranks"]
worst = max(float(r["rank_imbalance"]) for r in rows)
limit = 1 + ranks["rebalance_threshold"]
if ranks["partitions_made"] < 2: sys.exit(f"no repartition ({ranks})")
if worst > limit: sys.exit(f"imbalance {worst} above {limit}")
done = ranks["evaluation_imbalance"]
if done > limit: sys.exit(f"bond evaluations' imbalance {done} above {limit}")
# Events bring their window up to date, not every node (the repartitioning ones everything).
if not 0 < ranks["window_events_resynced"] < ranks["window_events"]:
    sys.exit(f"events synced their windows in {ranks['window_events']}, everything in "
             f"{ranks['window_events_resynced']}")
print(f"imbalance <= {worst:.4f} over {len(rows)} rows, {ranks['partitions_made']} partitions, "
      f"{ranks['events_kept_partition']} events kept the partition; evaluations {done:.4f}; "
      f"{ranks['window_events']} events synced their windows, {ranks['window_events_resynced']} "
      f"of them everything after repartitioning")
PY
    ); then echo "ok   $name, $first ranks: $r"; else echo "FAIL $name: $r"; fail=1; fi
  fi
  # Restart on another rank count: the 2-rank checkpoint of step 100, continued on 3 ranks.
  if [[ $name == restart-* ]]; then
    ck="$tmp/$name-ck"
    mpirun -np 2 "$bin" run "$deck" --out "$ck" "${args[@]}" --set output.checkpoint_every=100 \
      > "$ck.log" 2>&1 || { echo "FAIL $name: checkpointing run"; fail=1; continue; }
    # Into the same folder, whose earlier snapshots the restart keeps.
    if mpirun -np 3 "$bin" run "$deck" --out "$ck" "${args[@]}" --restart "$ck/checkpoint.bin" \
         > "$ck-restart.log" 2>&1 && r=$(same "$tmp/$name-1" "$ck" 2>&1); then
      echo "ok   $name: checkpoint of a 2-rank run restarted on 3: $r"
    else
      echo "FAIL $name: restart on 3 ranks: ${r:-$(tail -3 "$ck-restart.log")}"; fail=1
    fi
  fi
  # Held rows checkpoint in pieces, one per rank, beside checkpoint.bin (the last checkpoint's
  # alone: the 3-rank restart wrote none); a piece missing, of another checkpoint or damaged is
  # refused (exit 2) naming it; a serial run restarts from them, and a serial run's checkpoint
  # restarts on 2 ranks that hold their rows (names restart-pieces-*; the other held restarts read
  # pieces in the 2-to-3 restart above).
  if [[ $name == restart-pieces-* ]]; then
    pieces=($(cd "$tmp/$name-ck" && ls checkpoint.rows.* 2> /dev/null))
    step=${pieces[0]#checkpoint.rows.}; step=${step%%.*}
    if [[ ${pieces[*]} == "checkpoint.rows.$step.0-of-2.bin checkpoint.rows.$step.1-of-2.bin" ]]; then
      echo "ok   $name: the checkpoint's bond rows in pieces: ${pieces[*]}"
    else echo "FAIL $name: pieces beside the checkpoint: '${pieces[*]}'"; fail=1; fi
    for bad in missing swapped damaged; do
      cb="$tmp/$name-$bad"; cp -r "$tmp/$name-ck" "$cb"
      case $bad in
        missing) rm -f "$cb/${pieces[1]}" ;;
        swapped) cp "$cb/${pieces[0]}" "$cb/${pieces[1]}" ;;
        damaged) python3 -c "import os, sys; p = sys.argv[1]; at = os.path.getsize(p) // 2; f = open(p, 'r+b'); f.seek(at); b = f.read(1); f.seek(at); f.write(bytes([b[0] ^ 1]))" "$cb/${pieces[1]}" ;;
      esac
      mpirun -np 2 "$bin" run "$deck" --out "$cb" "${args[@]}" --restart "$cb" > "$cb.log" 2>&1; rc=$?
      if [[ $rc -eq 2 ]] && grep -q "${pieces[1]}" "$cb.log"; then
        echo "ok   $name: a $bad piece refused: $(grep -m1 -o "${pieces[1]}.*" "$cb.log")"
      else echo "FAIL $name: a $bad piece: exit $rc: $(tail -2 "$cb.log")"; fail=1; fi
    done
    ck1="$tmp/$name-ck1"; ck2="$tmp/$name-ck2"
    mpirun -np 2 "$bin" run "$deck" --out "$ck1" "${args[@]}" --set output.checkpoint_every=100 \
      > "$ck1.log" 2>&1 && "$bin" run "$deck" --out "$ck1" "${args[@]}" --restart "$ck1" \
      > "$ck1-restart.log" 2>&1 && r=$(same "$tmp/$name-1" "$ck1" 2>&1) &&
      echo "ok   $name: pieces of a 2-rank run restarted serially: $r" ||
      { echo "FAIL $name: serial restart from pieces: ${r:-$(tail -3 "$ck1-restart.log")}"; fail=1; }
    "$bin" run "$deck" --out "$ck2" "${args[@]}" --set output.checkpoint_every=100 \
      > "$ck2.log" 2>&1 && mpirun -np 2 "$bin" run "$deck" --out "$ck2" "${args[@]}" --restart "$ck2" \
      > "$ck2-restart.log" 2>&1 && r=$(same "$tmp/$name-1" "$ck2" 2>&1) &&
      python3 -c "import json, sys; sys.exit(not json.load(open('$ck2/summary.json'))['ranks']['held_bond_rows'])" &&
      echo "ok   $name: a serial checkpoint restarted on 2 ranks holding their rows: $r" ||
      { echo "FAIL $name: 2-rank restart from a serial checkpoint: ${r:-$(tail -3 "$ck2-restart.log")}"; fail=1; }
  fi
done
# An output failure meets rank 0 alone (it writes the files): every rank stops, exit code 4.
first_deck=$(ls "$(dirname "$0")/../examples/crack_branching_2d.yaml")
timeout 120 mpirun -np 2 "$bin" run "$first_deck" --out /proc/periadapt-no-folder --quiet \
  --threads 1 --set solver.end_time=1e-6 > "$tmp/outfail.log" 2>&1; rc=$?
if [[ $rc -eq 4 ]]; then echo "ok   an output failure on rank 0 stops all ranks (exit 4)"
else echo "FAIL output failure under mpirun: exit $rc: $(head -3 "$tmp/outfail.log")"; fail=1; fi
# A command rank 0 runs alone (a sweep) finishes without waiting for the ranks that left.
timeout 120 mpirun -np 2 "$bin" sweep "$first_deck" --set solver.end_time=2e-6,3e-6 --out "$tmp/sweep" \
  --quiet --threads 1 > "$tmp/sweep.log" 2>&1; rc=$?
if [[ $rc -eq 0 && $(wc -l < "$tmp/sweep/sweep.csv") -eq 3 ]]; then echo "ok   a sweep under mpirun runs on rank 0 alone"
else echo "FAIL sweep under mpirun: exit $rc: $(tail -2 "$tmp/sweep.log")"; fail=1; fi
# A diverging run stops every rank at the step and node the serial run reports (exit 3): the
# lowest offending node over the ranks' regions.
unstable=(--quiet --threads 1 --set solver.time_step=4e-7 --set solver.allow_unstable_time_step=true
          --set solver.end_time=1e-4)
"$bin" run "$first_deck" --out "$tmp/dv-1" "${unstable[@]}" > /dev/null 2>&1; rc1=$?
timeout 120 mpirun -np 3 "$bin" run "$first_deck" --out "$tmp/dv-3" "${unstable[@]}" > /dev/null 2>&1; rc3=$?
if r=$(python3 - "$tmp/dv-1" "$tmp/dv-3" <<'PY'
import json, os, sys
a, b = (json.load(open(os.path.join(d, "summary.json"))).get("divergence") for d in sys.argv[1:3])
if a is None or a != b: sys.exit(f"serial {a}, 3 ranks {b}")
print(f"node {a['node']} at step {a['step']}")
PY
) && [[ $rc1 -eq 3 && $rc3 -eq 3 ]]; then echo "ok   divergence on 3 ranks as on 1: $r, exit 3"
else echo "FAIL divergence under mpirun: exit $rc1 / $rc3: $r"; fail=1; fi
exit $fail
