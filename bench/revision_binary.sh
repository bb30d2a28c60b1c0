#!/usr/bin/env bash
# Prints the path of REV's periadapt binary, building REV (optimized, no tests) in a scratch
# folder the first time: the earlier revision of the comparison scripts (compare_revisions.sh,
# event_cost.sh).
#   bash bench/revision_binary.sh REV
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bench/revision_binary.sh REV}
work=${TMPDIR:-/tmp}/periadapt-rev-$(git rev-parse --short "$rev")
if [[ ! -x $work/build/periadapt ]]; then
  rm -rf "$work/src"; mkdir -p "$work/src"
  git archive "$rev" | tar -xf - -C "$work/src"
  cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DPERIADAPT_BUILD_TESTS=OFF \
    -DPERIADAPT_BUILD_BENCH=OFF > /dev/null
  cmake --build "$work/build" -j"$(nproc)" > "$work/build.log" 2>&1 ||
    { tail -20 "$work/build.log" >&2; exit 1; }
fi
echo "$work/build/periadapt"
