#!/usr/bin/env bash
# Mutation testing (a developer script, not CI): applies each one-line bug of scripts/mutants.tsv
# to a scratch copy of the working tree, rebuilds, runs the test suite and prints whether a test
# failed (killed) or none did (survived), with the failing tests.
#
#   bash scripts/mutation-check.sh [--only ID,ID...] [--killers | --full] [--work DIR] [--list FILE]
#
# The fast tests (everything but validation_*) run first, up to the first failure; the validations
# only for a mutant the fast tests let through. --killers runs every fast test (so every fast test
# that kills it is listed), --full the whole suite, validations included. A mutant
# whose pattern does not match exactly once stops the script (the list is stale); one that does
# not compile is reported as stillborn and left out of the score. Results also go to
# WORK/results.tsv. Takes about 1-3 minutes per mutant on 2 cores (more with --full).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
list=scripts/mutants.tsv
work=${TMPDIR:-/tmp}/periadapt-mutants
only=""
full=0
killers=0
while (($#)); do
  case $1 in
    --only) only=$2; shift 2 ;;
    --full) full=1; shift ;;
    --killers) killers=1; shift ;;
    --work) work=$2; shift 2 ;;
    --list) list=$2; shift 2 ;;
    *) echo "usage: $0 [--only ID,ID...] [--killers | --full] [--work DIR] [--list FILE]" >&2; exit 2 ;;
  esac
done
list=$(realpath "$list")
jobs=$(nproc)

# Scratch copy of the working tree (tracked and untracked, not ignored), built once. A file
# whose content differs from the previous copy's is written anew (a fresh time, so make rebuilds
# it); unchanged files keep their time, so the scratch build only rebuilds what changed. (Copying
# the tree's own times instead would miss a file edited before the previous scratch build ran.)
mkdir -p "$work/src"
rm -rf "$work/incoming"
mkdir -p "$work/incoming"
git ls-files -co --exclude-standard -z | tar -cf - --null -T - | tar -xf - -C "$work/incoming"
(cd "$work/incoming" && find . -type f -print0) | while IFS= read -r -d '' f; do
  if ! cmp -s "$work/incoming/$f" "$work/src/$f"; then
    mkdir -p "$(dirname "$work/src/$f")"
    cp "$work/incoming/$f" "$work/src/$f"
  fi
done
(cd "$work/src" && find . -type f -print0) | while IFS= read -r -d '' f; do
  [[ -e $work/incoming/$f ]] || rm -f "$work/src/$f"
done
rm -rf "$work/incoming"
# Files a stopped earlier call left built mutated: make them rebuild.
if [[ -f $work/dirty ]]; then
  while read -r f; do [[ -f $work/src/$f ]] && touch "$work/src/$f"; done < "$work/dirty"
fi
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DPERIADAPT_BUILD_BENCH=OFF > /dev/null
echo "building the unmutated scratch copy in $work ..."
cmake --build "$work/build" -j"$jobs" > "$work/build.log" 2>&1 || { tail -30 "$work/build.log"; exit 1; }

failed_tests() {  # ctest arguments...; prints the failing tests' names, one per line
  rm -f "$work/build/Testing/Temporary/LastTestsFailed.log"
  OMP_WAIT_POLICY=PASSIVE ctest --test-dir "$work/build" -j"$jobs" --timeout 600 "$@" \
    > "$work/ctest.log" 2>&1 || true
  [[ -f $work/build/Testing/Temporary/LastTestsFailed.log ]] &&
    sed 's/^[0-9]*://' "$work/build/Testing/Temporary/LastTestsFailed.log" || true
}

echo "checking that the unmutated suite passes ..."
base_fail=$(failed_tests)
if [[ -n $base_fail ]]; then
  echo "the unmutated suite fails; fix it first:" >&2
  echo "$base_fail" >&2
  exit 1
fi

results="$work/results.tsv"
printf "id\tresult\ttests\tdescription\n" > "$results"
killed=0; survived=0; stillborn=0
survivors=()
while IFS=$'\t' read -r id file subst desc; do
  [[ -z $id || $id == \#* ]] && continue
  if [[ -n $only && ",$only," != *",$id,"* ]]; then continue; fi
  target="$work/src/$file"
  [[ -f $target ]] || { echo "$id: no file $file" >&2; exit 1; }
  n=$(SUBST="$subst" perl -0ne '$n = eval "\$_ =~ $ENV{SUBST}g"; die $@ if $@; print $n + 0' "$target")
  if [[ $n != 1 ]]; then
    echo "$id: its pattern matches $n times in $file (expected once); update $list" >&2
    exit 1
  fi
  cp "$target" "$work/pristine"
  echo "$file" >> "$work/dirty"
  SUBST="$subst" perl -0pi -e 'eval "\$_ =~ $ENV{SUBST}"; die $@ if $@' "$target"
  if cmp -s "$target" "$work/pristine"; then
    echo "$id: the substitution left $file unchanged" >&2; exit 1
  fi
  t0=$SECONDS
  if ! cmake --build "$work/build" -j"$jobs" > "$work/build.log" 2>&1; then
    result=stillborn; tests="(does not compile)"; stillborn=$((stillborn + 1))
  else
    if ((full)); then
      tests=$(failed_tests)
    elif ((killers)); then
      tests=$(failed_tests -E '^validation_')
      [[ -z $tests ]] && tests=$(failed_tests --stop-on-failure -R '^validation_')
    else
      tests=$(failed_tests --stop-on-failure -E '^validation_')
      [[ -z $tests ]] && tests=$(failed_tests --stop-on-failure -R '^validation_')
    fi
    if [[ -n $tests ]]; then
      result=killed; killed=$((killed + 1))
    else
      result=survived; survived=$((survived + 1)); survivors+=("$id")
    fi
    tests=$(echo "$tests" | paste -sd, -)
  fi
  cp "$work/pristine" "$target"
  touch "$target"
  printf "%-26s %-9s %4ds  %s\n" "$id" "$result" $((SECONDS - t0)) "${tests:-}"
  printf "%s\t%s\t%s\t%s\n" "$id" "$result" "${tests:-}" "$desc" >> "$results"
done < "$list"

# Leave the scratch build unmutated for the next call.
cmake --build "$work/build" -j"$jobs" > "$work/build.log" 2>&1 && rm -f "$work/dirty"
total=$((killed + survived))
((total > 0)) || { echo "no mutant selected"; exit 2; }
echo "killed $killed of $total ($(( 100 * killed / total ))%), stillborn $stillborn"
((survived == 0)) || echo "survivors: ${survivors[*]}"
