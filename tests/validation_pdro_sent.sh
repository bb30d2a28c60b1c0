#!/usr/bin/env bash
# Medium validation (CI): Stewart & Jeon 3.2, single-edge-notched tension on the 1 mm grid
# (20,000 nodes, a few seconds per run). The plain run fails within 15% of the LEFM stress of
# Eqs. 11-12 (PD with G0-calibrated s0 reproduces K_IC; we measure +1.2%), and the refinement
# overlay with n = 2 keeps the failure stress within 10% of the plain run and within 15% of
# LEFM (toughness preserved, the paper's claim; we measure +4.3%). With n = 5 the overlay
# toughens this notch by 25% (three_pairs) and 15% (whole_bond) with the notch end at 25.0 mm,
# 24.8 mm or 25.2 mm alike: printed, not asserted. The +9.6% once measured at n = 5 came from
# bonds through the notch end cut in one direction only (docs/agrs.md, "Bonds through a crack's
# end").
set -u
bin="$1"; deck="$2"; out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" study pdro-sent --quick --deck "$deck" --out "$out" > "$out/log.txt" 2>&1 || { cat "$out/log.txt"; echo "FAIL: study"; exit 1; }
cat "$out/log.txt"
# pdro_sent.csv: dx_m,overlay_n,nodes,failure_stress_Pa,lefm_Pa,... ; row 2 plain, then n = 2, 5.
awk -F, 'NR == 2 { plain = $4; lefm = $5 } NR > 2 { n[NR] = $2; ovl[NR] = $4 }
  END {
    if (!(plain > 0) || NR < 4) { print "FAIL: no plain failure or missing overlay runs"; exit 1 }
    bad = 0; r1 = plain / lefm
    if (r1 < 0.85 || r1 > 1.15) { printf "FAIL: plain / LEFM = %.3f\n", r1; bad = 1 }
    printf "plain / LEFM %.3f\n", r1
    for (k = 3; k <= NR; ++k) {
      if (!(ovl[k] > 0)) { printf "FAIL: no failure with n = %s\n", n[k]; bad = 1; continue }
      r2 = ovl[k] / plain; r3 = ovl[k] / lefm
      asserted = (n[k] + 0 <= 2)
      if (asserted && (r2 < 0.90 || r2 > 1.10)) { printf "FAIL: overlay(n=%s) / plain = %.3f\n", n[k], r2; bad = 1 }
      if (asserted && (r3 < 0.85 || r3 > 1.15)) { printf "FAIL: overlay(n=%s) / LEFM = %.3f\n", n[k], r3; bad = 1 }
      printf "overlay(n=%s) / plain %.3f, / LEFM %.3f%s\n", n[k], r2, r3, asserted ? "" : " (not asserted)"
    }
    exit bad
  }' "$out/pdro_sent.csv"
