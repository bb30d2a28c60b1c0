#!/usr/bin/env bash
# Each bad deck must exit with code 2 and an error naming the file, the key and the line.
set -u
bin="$1"; dir="$2"; fail=0
check() {  # deck expected-substring
  out=$(timeout 60 "$bin" check "$dir/$1" 2>&1); rc=$?  # a hang is a finding too
  if [[ $rc -ne 2 ]]; then echo "FAIL $1: exit code $rc (want 2): $out"; fail=1; return; fi
  if [[ "$out" != *"$2"* ]]; then echo "FAIL $1: message lacks '$2': $out"; fail=1; return; fi
  echo "ok   $1: $out"
}
check unknown_key.yaml "unknown_key.yaml:5:3: key 'material.fracture_enrgy': unknown key; did you mean 'fracture_energy'?"
check negative_modulus.yaml "negative_modulus.yaml:3:19: key 'material.youngs_modulus': must be > 0"
check malformed.yaml "malformed.yaml:4:"
check overlay_dual_horizon.yaml "overlay_dual_horizon.yaml:5:3: key 'damage': the refinement overlay works with bond_pairing: source_horizon"
check overlay_sampling.yaml "overlay_sampling.yaml:5:29: key 'damage.overlay.sampling': 'everywhere' is not allowed; allowed: three_pairs, whole_bond"
check multirate_lps.yaml "multirate_lps.yaml:7:14: key 'solver.multirate': multi-rate stepping needs row-local forces: formulation: pmb"
check lattice_lps.yaml "lattice_lps.yaml:6:29: key 'discretization.micromodulus_calibration': lattice calibrates bond-based micromoduli"
check yaml_comma_line.yaml "yaml_comma_line.yaml: a deck is a YAML mapping"
check static_free.yaml "static_free.yaml:8:16: key 'solver.type': a static solve needs boundary_conditions that prescribe displacements"
check contact_static.yaml "contact_static.yaml:9:12: key 'contact.enabled': contact forces are for explicit runs"
check impactor_axis.yaml "impactor_axis.yaml:9:78: key 'impactors[0].axis': a sphere has no length or axis"
check body_outside.yaml "body_outside.yaml:5:9: key 'discretization.body': the body cannot be an outside (complement) region"
check blocks_dual_horizon.yaml "blocks_dual_horizon.yaml:5:3: key 'blocks': several materials work with bond_pairing: source_horizon"
check blocks_poisson_pmb.yaml "blocks_poisson_pmb.yaml:6:93: key 'blocks[0].material.poisson_ratio': the bond-based PMB model fixes Poisson's ratio of every block"
check blocks_no_nodes.yaml "blocks_no_nodes.yaml:6:13: key 'blocks[0].region': the region selects no nodes"
check blocks_no_fracture.yaml "blocks_no_fracture.yaml:6:15: key 'blocks[0].material': damage is enabled: give this block's fracture_energy"
check ghost_dual_horizon.yaml "ghost_dual_horizon.yaml:5:41: key 'adapt.ghost_correction': the correction acts on each row's own force"
check ghost_static.yaml "ghost_static.yaml:11:21: key 'adapt.ghost_correction': the static solver assembles the bond stiffness directly"
check gmsh_exit.yaml "gmsh_exit.yaml:6:16: key 'discretization.body.gmsh': "
check gmsh_bowtie.yaml "gmsh_bowtie.yaml:6:16: key 'discretization.body.gmsh': "
check stl_overlap.yaml "stl_overlap.yaml:6:19: key 'discretization.body.surface': "
# run refuses a time step above the finest level's stable step; so must check.
check adapt_time_step.yaml "adapt_time_step.yaml:4:21: key 'solver.time_step': 1.5e-07 s exceeds the stable step expected at refinement level 1"
check list_key.yaml "list_key.yaml:2:1: a key must be a plain name"
check empty_key.yaml "empty_key.yaml:2:3: a key must be a plain name"
check end_time_huge.yaml "end_time_huge.yaml: key 'solver.end_time': gives inf steps"
check time_step_tiny.yaml "time_step_tiny.yaml: key 'solver.end_time': gives 1e+294 steps"
check end_time_zero_steps.yaml "end_time_zero_steps.yaml: key 'solver.end_time': gives 0 steps"
check vtu_snapshots_huge.yaml "vtu_snapshots_huge.yaml:5:25: key 'output.vtu_snapshots': must be in 0 ... 100000"
# A crack along a node row would be bridged by those nodes' bonds to both faces.
check precrack_on_nodes.yaml "precrack_on_nodes.yaml:7:5: key 'cracks[0]': the pre-crack passes through 8 nodes (the first at (0.0005, 0.0055, 0) m)"
check rebalance_threshold.yaml "rebalance_threshold.yaml:6:24: key 'solver.rebalance_threshold': must be in [0.01, 10]"
# Impossible memory: refused from the deck alone, within 2 s and under a 3 GB address-space cap,
# with the estimate in the message.
mem() {  # deck expected-substring
  # (Not under AddressSanitizer, whose shadow memory needs the address space.)
  out=$([[ -n ${PERIADAPT_SANITIZE:-} ]] || ulimit -v 3000000; timeout 2 "$bin" check "$dir/$1" 2>&1); rc=$?
  if [[ $rc -ne 2 || "$out" != *"$2"* || "$out" != *"the deck asks for about"* ]]; then
    echo "FAIL $1: exit code $rc: $out"; fail=1; return; fi
  echo "ok   $1: $out"
}
mem memory_spacing.yaml "key 'discretization.spacing'"
mem memory_horizon.yaml "this machine has available"
mem memory_levels.yaml "at most 2^31 nodes"
mem memory_limit.yaml "key 'solver.memory_limit_gb'"
# Not a regular file: refused before reading (/dev/zero would be read without bound).
for f in /dev/zero "$dir"; do
  out=$(timeout 10 "$bin" check "$f" 2>&1); rc=$?
  [[ $rc -eq 2 && "$out" == *"is not a regular file"* ]] && echo "ok   $f: $out" || { echo "FAIL $f: $rc $out"; fail=1; }
done
out=$("$bin" run "$dir/unknown_key.yaml" --threads 0 2>&1); rc=$?
[[ $rc -eq 2 && "$out" == *"--threads: Value 0 not in range 1 to 4096"* ]] && echo "ok   --threads 0: $out" || { echo "FAIL --threads 0: $rc $out"; fail=1; }
out=$("$bin" check "$dir/does_not_exist.yaml" 2>&1); rc=$?
[[ $rc -eq 2 && "$out" == *"cannot open"* ]] && echo "ok   missing file: $out" || { echo "FAIL missing file: $rc $out"; fail=1; }
# Only a solve can tell that a held static system is still singular: `run`, not `check`.
tmp=$(mktemp -d)
out=$("$bin" run "$dir/static_unconstrained.yaml" --out "$tmp" --quiet 2>&1); rc=$?
rm -rf "$tmp"
[[ $rc -eq 2 && "$out" == *"static_unconstrained.yaml"* && "$out" == *"singular system"* ]] \
  && echo "ok   static_unconstrained.yaml: $out" || { echo "FAIL static_unconstrained.yaml: $rc $out"; fail=1; }
# A refinement event that leaves the step above the refined rows' bound stops the run after that
# step with its outputs finished: exit 3, the node and step named, summary status
# unstable_time_step, no .part left.
tmp=$(mktemp -d)
out=$("$bin" run "$dir/adapt_unstable_after_event.yaml" --out "$tmp" --quiet 2>&1); rc=$?
status=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["status"])' "$tmp/summary.json" 2>&1)
parts=$(ls "$tmp" | grep -c '\.part$')
[[ $rc -eq 3 && "$out" == *"made the time step unstable"* && "$out" == *"node "* && "$out" == *"solver.time_step to"* &&
   "$status" == unstable_time_step && $parts -eq 0 && -s "$tmp/history.csv" && -s "$tmp/refinement.csv" ]] \
  && echo "ok   adapt_unstable_after_event.yaml: $out" ||
  { echo "FAIL adapt_unstable_after_event.yaml: rc $rc, status $status, $parts .part files: $out"; fail=1; }
rm -rf "$tmp"
# At the default safety factor the default step holds through every event: the moments
# correction's refits keep the refined rows' bound at the uniform fine grid's.
tmp=$(mktemp -d)
out=$("$bin" run "$dir/adapt_unstable_after_event.yaml" --out "$tmp" --quiet \
      --set solver.safety_factor=0.8 2>&1); rc=$?
status=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["status"])' "$tmp/summary.json" 2>&1)
[[ $rc -eq 0 && "$status" == completed ]] \
  && echo "ok   adapt_unstable_after_event.yaml at safety factor 0.8: completed" ||
  { echo "FAIL adapt_unstable_after_event.yaml at safety factor 0.8: rc $rc, $status: $out"; fail=1; }
rm -rf "$tmp"
# With solver.allow_unstable_time_step the user takes that step knowingly: the event does not
# stop the run (the divergence check would, were it to blow up).
tmp=$(mktemp -d)
out=$("$bin" run "$dir/adapt_unstable_after_event.yaml" --out "$tmp" --quiet \
      --set solver.allow_unstable_time_step=true 2>&1); rc=$?
status=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["status"])' "$tmp/summary.json" 2>&1)
[[ "$out" != *"made the time step unstable"* && ( $rc -eq 0 && "$status" == completed ||
   $rc -eq 3 && "$status" == diverged ) ]] \
  && echo "ok   adapt_unstable_after_event.yaml with allow_unstable_time_step: rc $rc, $status" ||
  { echo "FAIL adapt_unstable_after_event.yaml with allow_unstable_time_step: rc $rc, $status: $out"; fail=1; }
rm -rf "$tmp"
# Empty --restart or --out values (an unset shell variable) are refused, not read as "none":
# an empty --restart started the run over and replaced its checkpoint.
for opt in --restart --out; do
  out=$("$bin" run "$dir/unknown_key.yaml" $opt "" 2>&1); rc=$?
  [[ $rc -eq 2 && "$out" == *"key '$opt': is empty"* ]] && echo "ok   empty $opt: $out" ||
    { echo "FAIL empty $opt: $rc $out"; fail=1; }
done
# A study's or a sweep's folder that cannot be made: exit 4 naming it, not a C++ exception.
out=$("$bin" study weak-directions --out "$dir/unknown_key.yaml" 2>&1); rc=$?
[[ $rc -eq 4 && "$out" == *"cannot create the output folder"* ]] && echo "ok   study --out a file: $out" ||
  { echo "FAIL study --out a file: $rc $out"; fail=1; }
# A runaway impactor stops the run as a divergence naming it, with no NaN in history.csv's energies.
tmp=$(mktemp -d)
out=$("$bin" run "$dir/impactor_runaway.yaml" --out "$tmp" --quiet --threads 1 2>&1); rc=$?
nan=$(cut -d, -f3-6 "$tmp/history.csv" 2>/dev/null | grep -ci nan)
[[ $rc -eq 3 && "$out" == *"impactors[0]: non-finite"* && $nan -eq 0 ]] && echo "ok   impactor_runaway.yaml: $out" ||
  { echo "FAIL impactor_runaway.yaml: rc $rc, $nan NaN rows: $out"; fail=1; }
rm -rf "$tmp"
exit $fail
