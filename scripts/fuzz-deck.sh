#!/usr/bin/env bash
# Fuzzes the deck loader with libFuzzer (clang, Debian) for SECONDS (default 90): the examples and
# the bad decks of the tests are the seed corpus, fuzz/deck.dict the keys. Any finding (a crash,
# an exception other than DeckError, a sanitizer report, a timeout, a large allocation) fails the
# script and leaves the input in OUT/ (crash-*, timeout-*, oom-*): make it a regression test in
# tests/bad_decks. usage: scripts/fuzz-deck.sh [SECONDS] [OUT]
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${1:-90}"; out="${2:-build/fuzz}"
if ! command -v clang++ > /dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends clang > /dev/null
fi
mkdir -p "$out/corpus"
flags=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -Isrc)
sources=(fuzz/deck_fuzzer.cpp fuzz/surface_mesh_stub.cpp src/input/deck*.cpp
  src/input/yaml_section.cpp src/input/point_cloud.cpp src/discretize/grid.cpp
  src/core/expression.cpp src/setup/memory_estimate.cpp src/material/micromodulus.cpp
  src/material/bond_laws.cpp src/material/formulation.cpp $(grep -l bond_law_kernel.hpp src/material/*.cpp))
# One object per source, compiled side by side (one clang++ call compiles them one after another).
rm -rf "$out/obj"; mkdir -p "$out/obj"
printf '%s\n' "${sources[@]}" | sort -u | xargs -P "$(nproc)" -I{} sh -c \
  'clang++ "$@" -c "{}" -o "'"$out"'/obj/$(echo "{}" | tr / _).o"' _ "${flags[@]}"
clang++ "${flags[@]}" "$out"/obj/*.o -lyaml-cpp -lmuparser -lfmt -o "$out/deck_fuzzer"
dict="$PWD/fuzz/deck.dict"
seeds="$out/seeds"; rm -rf "$seeds"; mkdir -p "$seeds"
cp examples/*.yaml tests/bad_decks/*.yaml bench/agrs/*.yaml "$seeds"/
cd "$out"
# -rss_limit_mb: a deck may not make the loader allocate without bound; -timeout: nor hang.
./deck_fuzzer -max_total_time="$secs" -dict="$dict" -max_len=8192 -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 corpus seeds 2>&1 | tail -25
