#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc, -O1), in build-asan/.
# Leaks are reported too; scripts/lsan.supp suppresses third-party ones only. The long fracture
# validations are left to the optimized build (scripts/test.sh): under the sanitizers they would
# take most of CI's time and exercise the same code as the medium ones that do run here (so do the
# two wave-reflection checks: the lattice moment and the density jump have unit tests that run).
# Three unit tests that repeat smaller ones' code on larger grids stay out as well (30-50 s each
# here): the LPS stress with the moments correction (the PMB stress test runs the correction and
# cli_vtu_stress the LPS stress), the isotropic expansion at m = 6 (m = 3 runs) and the wave through
# an interface-horizon patch (every adaptive test runs the correction). So do three physics tests of
# 20-40 s each under the sanitizers whose code smaller tests run (the uniaxial P-wave modulus,
# Bobaru's arrival times, the overlay's sqrt(n) strength) and
# cli_bond_laws (the laws' unit and conformance tests run here); cli_restart kills and restarts
# only its first two decks here (PERIADAPT_SANITIZE, below).
set -euo pipefail
cd "$(dirname "$0")/.."
# Unity batches and line-table debug info (enough for the reports' stack traces) keep this
# build, CI's largest single step, short.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DPERIADAPT_NATIVE=OFF -DPERIADAPT_BUILD_BENCH=OFF \
  -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
cmake --build build-asan -j"$(nproc)" > build-asan/build.log 2>&1 || { tail -40 build-asan/build.log; exit 1; }
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export PERIADAPT_SANITIZE=1  # tests that cap the address space skip the cap (ASan reserves terabytes)
# ctest runs tests side by side, each with an OpenMP thread per core: threads that spin at
# barriers then take the cores the other test needs (a pair of tests ran in 28.6 s spinning,
# 18.4 s waiting passively). The wait policy changes no result.
export OMP_WAIT_POLICY=PASSIVE
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" --timeout 900 \
  -E "validation_(grid_orientation|pdro_sent|sent_levels|kalthoff_winkler|beam_3pb_lps|density_jump)|Adapt.LatticeCalibrationRemoves|cli_mpi|cli_bond_laws|Stress.LpsStressIsClassicalUpToTheSurface|EnergyDensity.IsotropicExpansionMatchesClassicalAtM6|Adapt.InterfaceHorizonLowersTheLocalEnergyLoss|EnergyDensity.UniaxialStrainGivesBondBasedPWaveModulus|Dynamics.BobaruWaveArrivalTimes|Pdro.OverlayRaisesTheStrength"
