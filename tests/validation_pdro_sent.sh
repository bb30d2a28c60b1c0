#!/usr/bin/env bash
# Medium validation (CI): Stewart & Jeon 3.2, single-edge-notched tension on the 1 mm grid
# (20,000 nodes, a few seconds per run). The plain run fails within 15% of the LEFM stress of
# Eqs. 11-12 (PD with G0-calibrated s0 reproduces K_IC; we measure +2.6%), and the refinement
# overlay with n = 2 keeps the failure stress within 10% of the plain run (toughness preserved,
# the acceptance of the PDRO issue; we measure +2.7%).
set -u
bin="$1"; deck="$2"; out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" study pdro-sent --quick --deck "$deck" --out "$out" > "$out/log.txt" 2>&1 || { cat "$out/log.txt"; echo "FAIL: study"; exit 1; }
cat "$out/log.txt"
# pdro_sent.csv: dx_m,overlay_n,nodes,failure_stress_Pa,lefm_Pa,... ; row 2 plain, row 3 n = 2.
awk -F, 'NR == 2 { plain = $4; lefm = $5 } NR == 3 { ovl = $4 }
  END {
    if (!(plain > 0) || !(ovl > 0)) { print "FAIL: no failure in a run"; exit 1 }
    r1 = plain / lefm; r2 = ovl / plain; bad = 0
    if (r1 < 0.85 || r1 > 1.15) { printf "FAIL: plain / LEFM = %.3f\n", r1; bad = 1 }
    if (r2 < 0.90 || r2 > 1.10) { printf "FAIL: overlay / plain = %.3f\n", r2; bad = 1 }
    printf "plain / LEFM %.3f, overlay(n=2) / plain %.3f\n", r1, r2; exit bad
  }' "$out/pdro_sent.csv"
