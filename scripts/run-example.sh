#!/usr/bin/env bash
# Sets up (Debian packages, build) and runs the default example: adaptive dynamic crack branching in
# soda-lime glass (thesis 6.1). Writes VTU/PVD, damage PNGs, history.csv and summary.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
deck="${1:-examples/crack_branching_2d_adaptive.yaml}"
out="${2:-out/$(basename "$deck" .yaml)}"
./build/periadapt run "$deck" --out "$out"
