#!/usr/bin/env bash
# Medium validation (CI): Kalthoff-Winkler impact (thesis 6.2) with AGRS, levels 1 and 2
# (examples/kalthoff_winkler_2d_adaptive.yaml; about 2 s per run). Published: primary crack at
# 68 deg (experiment about 70), maximum tip speed 1,981 m/s, below the Rayleigh speed 2,799 m/s.
# Acceptance: 68 +- 4 deg, tip speed within 20% of 1,981 m/s and below 2,799 m/s, and the upper
# primary crack runs through to the top edge (y >= 190 mm of 200): we measure 69.1 / 65.6 deg,
# 1,963 / 1,891 m/s, and the level-1 tip ends at y = 199.5 mm. With the plate turned by 90 deg
# (the deck's old geometry) the cracks arrested 13 mm from the notches and this fails.
set -u
bin="$1"; deck="$2"; out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Level 2 as in the thesis: 54 us, dt halved for the finer level's stable step.
sed 's/max_level: 1/max_level: 2/; s/time_step: 70.0e-9/time_step: 35.0e-9/; s/end_time: 90.0e-6/end_time: 54.0e-6/' \
  "$deck" > "$out/level2.yaml"
for l in 1 2; do
  d="$deck"; [[ $l == 2 ]] && d="$out/level2.yaml"
  "$bin" run "$d" --out "$out/L$l" --quiet > "$out/L$l.log" 2>&1 || { cat "$out/L$l.log"; echo "FAIL: run level $l"; exit 1; }
done
val() { grep -m1 "\"$2\"" "$out/$1/summary.json" | sed -E 's/.*: *//; s/,$//'; }
tipy() { grep -m1 -A2 '"final_tip_m"' "$out/$1/summary.json" | tail -1 | tr -d ' ,'; }
awk -v a1="$(val L1 path_angle_deg)" -v v1="$(val L1 max_speed_m_s)" -v y1="$(tipy L1)" \
    -v a2="$(val L2 path_angle_deg)" -v v2="$(val L2 max_speed_m_s)" 'BEGIN {
  bad = 0
  printf "level 1: path angle %.2f deg, max tip speed %.0f m/s, final tip y = %.1f mm\n", a1, v1, 1e3 * y1
  printf "level 2: path angle %.2f deg, max tip speed %.0f m/s\n", a2, v2
  n = split(a1 " " a2, A, " "); split(v1 " " v2, V, " ")
  for (i = 1; i <= 2; ++i) {
    if (!(A[i] >= 64 && A[i] <= 72)) { printf "FAIL: level %d angle outside 68 +- 4 deg\n", i; bad = 1 }
    if (!(V[i] >= 0.8 * 1981 && V[i] <= 1.2 * 1981 && V[i] < 2799)) { printf "FAIL: level %d tip speed\n", i; bad = 1 }
  }
  if (!(y1 >= 0.19)) { print "FAIL: the level-1 primary crack does not reach the top edge"; bad = 1 }
  exit bad }'
