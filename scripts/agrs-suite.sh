#!/usr/bin/env bash
# The AGRS suite (docs/agrs.md, "The suite"): every deck of bench/agrs/ on its uniform coarse
# grid, its uniform fine grid and with the automatic profile (`adapt: {max_level: 1}`), compared
# with the fine run (crack path, damage sum, initiation, nodes, wall time; smallest of REPEATS
# alternating runs). Prints the table and writes it to bench/agrs/suite-table.md ($TABLE), with
# the machine and revision it was measured on. About a minute with REPEATS = 2 on 2 cores.
#   bash scripts/agrs-suite.sh [REPEATS] [suite.py options: --only a,b, --adapt key=value, ...]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=2
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then repeats=$1; shift; fi
[[ -x build/periadapt ]] || bash scripts/build.sh
table=${TABLE:-bench/agrs/suite-table.md}
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
status=0
python3 scripts/agrs/suite.py build/periadapt "$out" --repeat "$repeats" --table "$out/table.md" \
  "$@" || status=$?
{
  echo "<!-- scripts/agrs-suite.sh $repeats $*: $(git rev-parse --short HEAD 2>/dev/null || echo '?')," \
       "$(nproc) cores, $(date -u +%Y-%m-%d) -->"
  cat "$out/table.md"
} > "$table"
echo "table written to $table"
exit $status
