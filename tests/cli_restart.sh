#!/usr/bin/env bash
# Checkpoint / restart. For a uniform deck, an adaptive one (damage trigger with step redo,
# two-rate stepping) and, when given, one with a rigid impactor (its motion is solver state),
# one with several materials (each node's block is model state) and an adaptive LPS deck run
# with adapt.ghost_correction (the restart builds the table whole, the run built it per event): a
# run stopped by SIGTERM mid-way writes checkpoint.bin and exits 143; a run
# killed by SIGKILL leaves its last periodic checkpoint (output.checkpoint_every). Each restarts
# with --restart and must end bit for bit where an uninterrupted run ends: history.csv and
# refinement.csv (all but their wall-time columns), every snapshot the uninterrupted run lists,
# crack_speed.csv and summary.json (all but timings and paths). Then the refusals: another deck,
# a truncated file, a file that is no checkpoint.
set -u
bin="$1"; uniform="$2"; adaptive="$3"; impact="${4:-}"; blocks="${5:-}"; ghost="${6:-}"; fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
threads=2
ok() { echo "ok   $*"; }
bad() { echo "FAIL $*"; fail=1; }

same_outputs() {  # reference folder, folder
  python3 - "$1" "$2" <<'PY'
import json, os, re, sys
a, b = sys.argv[1], sys.argv[2]
def rows(d, f, drop_last):
    p = os.path.join(d, f)
    if not os.path.exists(p): return None
    return [",".join(l.rstrip("\n").split(",")[: -1 if drop_last else None]) for l in open(p)]
for f in ["history.csv", "refinement.csv"]:
    ra, rb = rows(a, f, True), rows(b, f, True)
    if ra != rb:
        n = next((i for i, (x, y) in enumerate(zip(ra or [], rb or [])) if x != y), None)
        sys.exit(f"{f} differs (line {n}: {ra[n] if n is not None else len(ra or [])} / "
                 f"{rb[n] if n is not None else len(rb or [])})")
if rows(a, "crack_speed.csv", False) != rows(b, "crack_speed.csv", False):
    sys.exit("crack_speed.csv differs")
files = re.findall(r'file="([^"]+)"', open(os.path.join(a, "snapshot.pvd")).read())
if files != re.findall(r'file="([^"]+)"', open(os.path.join(b, "snapshot.pvd")).read()):
    sys.exit("snapshot.pvd lists other files")
for f in files:
    if open(os.path.join(a, f), "rb").read() != open(os.path.join(b, f), "rb").read():
        sys.exit(f"{f} differs")
# The folder holds what the uninterrupted run's holds: no picture or snapshot of the moment the
# first run stopped is left beside the restarted run's.
def outputs(d):
    return sorted(f for f in os.listdir(d) if re.fullmatch(r"damage_.*us\.png|snapshot_\d+\.vtu", f))
if outputs(a) != outputs(b):
    sys.exit(f"other pictures or snapshots: {sorted(set(outputs(b)) ^ set(outputs(a)))}")
timing = {"wall_time_s", "setup_time_s", "solver_time_s", "sampling_time_s",
          "snapshot_output_time_s", "bond_evals_per_s", "family_build_time_s",
          "family_build_in_steps", "peak_rss_bytes", "rss_end_bytes", "refinement_wall_s", "restarted_from_step",
          "outputs", "threads", "event_wall_s"}
def strip(j):
    if isinstance(j, dict): return {k: strip(v) for k, v in j.items() if k not in timing}
    if isinstance(j, list): return [strip(v) for v in j]
    return j
sa = strip(json.load(open(os.path.join(a, "summary.json"))))
sb = strip(json.load(open(os.path.join(b, "summary.json"))))
if sa != sb:
    sys.exit("summary.json differs: " + ", ".join(f"{k}: {sa.get(k)} / {sb.get(k)}" for k in sa if sa.get(k) != sb.get(k)))
print(f"{len(files)} snapshots, history and summary equal")
PY
}

# Waits until the run has written history rows past `frac` of its steps (or has ended).
wait_for_step() {  # pid, folder, step
  for _ in $(seq 3000); do
    kill -0 "$1" 2> /dev/null || return
    local last
    last=$(tail -n 1 "$2/history.csv.part" 2> /dev/null | cut -d, -f1)
    [[ $last =~ ^[0-9]+$ ]] && ((last >= $3)) && return
    sleep 0.02
  done
}

# The impactor deck runs 15 us in a tenth of a second: longer here, so that a signal lands mid-run.
[[ -n $impact ]] && sed 's/end_time: 1.5e-5/end_time: 1.0e-4/' "$impact" > "$tmp/impact.yaml" && impact="$tmp/impact.yaml"
[[ -n $ghost ]] && sed 's/^adapt: {max_level: 1}/adapt: {max_level: 1, ghost_correction: true}/' "$ghost" > "$tmp/ghost.yaml" && ghost="$tmp/ghost.yaml"
[[ -z $ghost ]] || grep -q "ghost_correction: true" "$ghost" || { bad "ghost: no adapt line to extend"; ghost=""; }
for case in uniform adaptive ${impact:+impact} ${blocks:+blocks} ${ghost:+ghost}; do
  deck=${!case}
  steps=$("$bin" check "$deck" | sed -n "s/^steps  *\([0-9][0-9]*\) .*/\1/p" | head -1)
  [[ $steps =~ ^[0-9]+$ ]] || { bad "$case: no step count from check"; continue; }
  every=$((steps / 3))
  ref="$tmp/$case-ref"
  "$bin" run "$deck" --out "$ref" --quiet --threads $threads \
    --set output.checkpoint_every=$every > "$tmp/$case-ref.log" 2>&1 ||
    { bad "$case: reference run: $(cat "$tmp/$case-ref.log")"; continue; }

  # SIGTERM half-way: checkpoint, exit 143, restart.
  out="$tmp/$case-term"
  "$bin" run "$deck" --out "$out" --quiet --threads $threads > "$tmp/$case-term.log" 2>&1 &
  pid=$!
  wait_for_step $pid "$out" $((steps / 2))
  kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
  if [[ $rc -ne 143 || ! -s $out/checkpoint.bin ]]; then
    bad "$case SIGTERM: exit $rc (want 143 and checkpoint.bin): $(cat "$tmp/$case-term.log")"
  else
    at=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['steps_done'])" "$out/summary.json")
    "$bin" run "$deck" --out "$out" --quiet --threads $threads --restart "$out" \
      > "$tmp/$case-term2.log" 2>&1 || bad "$case SIGTERM restart: $(cat "$tmp/$case-term2.log")"
    msg=$(same_outputs "$ref" "$out" 2>&1) && ok "$case: SIGTERM at step $at of $steps, restarted: $msg" ||
      bad "$case: SIGTERM at step $at, restarted: $msg"
  fi

  # SIGKILL after the first periodic checkpoint: restart from it (under the sanitizers for the
  # first two decks only: the same reader as the SIGTERM restart above, at a sanitized run's cost).
  [[ -n ${PERIADAPT_SANITIZE:-} && $case != uniform && $case != adaptive ]] && continue
  out="$tmp/$case-kill"
  "$bin" run "$deck" --out "$out" --quiet --threads $threads \
    --set output.checkpoint_every=$every > "$tmp/$case-kill.log" 2>&1 &
  pid=$!
  for _ in $(seq 6000); do [[ -s $out/checkpoint.bin ]] && break; kill -0 $pid 2> /dev/null || break; sleep 0.01; done
  kill -KILL $pid 2> /dev/null; wait $pid 2> /dev/null
  if [[ ! -s $out/checkpoint.bin ]]; then
    bad "$case SIGKILL: no periodic checkpoint"
  else
    "$bin" run "$deck" --out "$out" --quiet --threads $threads --set output.checkpoint_every=$every \
      --restart "$out/checkpoint.bin" > "$tmp/$case-kill2.log" 2>&1 ||
      bad "$case SIGKILL restart: $(cat "$tmp/$case-kill2.log")"
    msg=$(same_outputs "$ref" "$out" 2>&1) && ok "$case: SIGKILL, restarted from the periodic checkpoint: $msg" ||
      bad "$case: SIGKILL, restarted: $msg"
  fi
done

# Refusals, exit 2, nothing written: another deck, a cut file, a file that is no checkpoint.
ck="$tmp/adaptive-ref/checkpoint.bin"
refuse() {  # name, expected text, run arguments...
  local name=$1 want=$2; shift 2
  local before; before=$(md5sum "$tmp/adaptive-ref/history.csv")
  "$bin" run "$adaptive" --out "$tmp/adaptive-ref" --quiet "$@" > "$tmp/refuse.log" 2>&1; local rc=$?
  if [[ $rc -eq 2 ]] && grep -q -- "$want" "$tmp/refuse.log" &&
     [[ $(md5sum "$tmp/adaptive-ref/history.csv") == "$before" ]]; then
    ok "refused: $name (exit 2)"
  else
    bad "$name: exit $rc, want 2 and '$want': $(cat "$tmp/refuse.log")"
  fi
}
refuse "another deck" "another deck" --restart "$ck" --set material.fracture_energy=100
head -c 5000 "$ck" > "$tmp/cut.bin"
refuse "a truncated checkpoint" "truncated" --restart "$tmp/cut.bin"
echo "not a checkpoint" > "$tmp/junk.bin"
refuse "a file that is no checkpoint" "not a PeriAdapt checkpoint" --restart "$tmp/junk.bin"
refuse "a folder without one" "no checkpoint here" --restart "$tmp"
# The header's step and time are checked with the data: a changed step is a corrupt file.
python3 - "$ck" "$tmp/step.bin" <<'PY'
import struct, sys
b = bytearray(open(sys.argv[1], "rb").read())
hsize = struct.unpack_from("<Q", b, 21 + 4)[0]
end = 21 + 4 + 8 + hsize  # the header's fields end with the step and the time (8 bytes each)
b[end - 16] ^= 0x01
open(sys.argv[2], "wb").write(bytes(b))
PY
refuse "a checkpoint whose step was changed" "checksum mismatch" --restart "$tmp/step.bin"
refuse "an end before the checkpoint" "not past its" --restart "$ck" --set solver.end_time=1.0e-8
# A longer run and other output settings are allowed: the deck's physics is what must match.
"$bin" run "$adaptive" --out "$tmp/longer" --quiet --restart "$ck" --set solver.end_time=60.0e-6 \
  --set output.vtu_snapshots=3 > "$tmp/longer.log" 2>&1 && ok "restart with a longer end_time" ||
  bad "restart with a longer end_time: $(cat "$tmp/longer.log")"
exit $fail
