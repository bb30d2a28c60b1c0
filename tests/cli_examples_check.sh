#!/usr/bin/env bash
# Every example deck passes `periadapt check` (parsed, validated, model built): a deck edited by
# hand, or one a code change made invalid, fails here rather than in a user's first run.
# Usage: cli_examples_check.sh PERIADAPT EXAMPLES_DIR
set -uo pipefail
exe=$1
dir=$2
fail=0
count=0
for deck in "$dir"/*.yaml; do
  count=$((count + 1))
  if ! out=$("$exe" check "$deck" 2>&1); then
    echo "FAIL: $deck"
    echo "$out" | tail -5
    fail=1
  fi
done
echo "$count example decks checked"
[[ $count -gt 0 ]] || { echo "no decks in $dir"; exit 1; }
exit $fail
