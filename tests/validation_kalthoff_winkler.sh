#!/usr/bin/env bash
# Medium validation (CI): Kalthoff-Winkler impact (thesis 6.2) with AGRS, levels 1 and 2
# (examples/kalthoff_winkler_2d_adaptive.yaml; about 2 s per run), against the uniform grid of
# level 1's spacing (1 mm, about 5 s). Published: primary crack at 68 deg (experiment about 70),
# maximum tip speed 1,981 m/s, below the Rayleigh speed 2,799 m/s.
# Acceptance:
# - level 1's path angle within 1 deg of the uniform 1 mm grid's (a lateral offset of one fine
#   spacing over the 60 mm path is 1 deg); measured 63.6 against 63.3 deg. The model gives
#   63.3 deg on uniform 1 mm and 63.6 deg on uniform 0.5 mm grids, not the thesis' 68 deg: the
#   adaptive runs' former 69.1 / 65.6 deg came from bonds through the notch tips cut in one
#   direction only (docs/agrs.md, "Bonds through a crack's end");
# - tip speeds within 20% of 1,981 m/s and below 2,799 m/s at both levels;
# - the upper primary crack runs through to the top edge (y >= 190 mm of 200).
# Level 2's angle (59.5 deg against the uniform 0.5 mm grid's 63.6) is printed, not asserted.
set -u
bin="$1"; deck="$2"; out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Level 2 as in the thesis: 54 us, dt halved for the finer level's stable step.
sed 's/max_level: 1/max_level: 2/; s/time_step: 70.0e-9/time_step: 35.0e-9/; s/end_time: 90.0e-6/end_time: 54.0e-6/' \
  "$deck" > "$out/level2.yaml"
# The uniform grid of level 1: the deck without its adapt section, at half the spacing.
sed '/^adapt:/,/^solver:/{/^solver:/!d}; s/spacing: 2.0e-3/spacing: 1.0e-3/; s/time_step: 70.0e-9/time_step: 35.0e-9/' \
  "$deck" > "$out/uniform.yaml"
for l in 1 2 U; do
  d="$deck"; [[ $l == 2 ]] && d="$out/level2.yaml"; [[ $l == U ]] && d="$out/uniform.yaml"
  "$bin" run "$d" --out "$out/L$l" --quiet > "$out/L$l.log" 2>&1 || { cat "$out/L$l.log"; echo "FAIL: run $l"; exit 1; }
done
val() { grep -m1 "\"$2\"" "$out/$1/summary.json" | sed -E 's/.*: *//; s/,$//'; }
tipy() { grep -m1 -A2 '"final_tip_m"' "$out/$1/summary.json" | tail -1 | tr -d ' ,'; }
# summary.json names the material's Rayleigh speed (2,834 m/s for E = 190 GPa, rho = 8000, nu = 1/4
# in plane strain: 0.9194 c_s) and whether a tracked tip outran it.
for l in 1 2; do
  cr=$(val L$l rayleigh_speed_m_s); above=$(val L$l max_speed_above_rayleigh)
  awk -v c="$cr" 'BEGIN { exit !(c > 2830 && c < 2838) }' || { echo "FAIL: level $l rayleigh_speed_m_s = $cr"; exit 1; }
  [[ "$above" == false ]] || { echo "FAIL: level $l max_speed_above_rayleigh = $above"; exit 1; }
done
awk -v a1="$(val L1 path_angle_deg)" -v v1="$(val L1 max_speed_m_s)" -v y1="$(tipy L1)" \
    -v a2="$(val L2 path_angle_deg)" -v v2="$(val L2 max_speed_m_s)" -v au="$(val LU path_angle_deg)" 'BEGIN {
  bad = 0
  printf "uniform 1 mm: path angle %.2f deg\n", au
  printf "level 1: path angle %.2f deg, max tip speed %.0f m/s, final tip y = %.1f mm\n", a1, v1, 1e3 * y1
  printf "level 2: path angle %.2f deg, max tip speed %.0f m/s\n", a2, v2
  d = a1 - au; if (d < 0) d = -d
  if (!(d <= 1.0)) { printf "FAIL: level 1 angle %.2f deg from the uniform grid'"'"'s\n", d; bad = 1 }
  split(v1 " " v2, V, " ")
  for (i = 1; i <= 2; ++i)
    if (!(V[i] >= 0.8 * 1981 && V[i] <= 1.2 * 1981 && V[i] < 2799)) { printf "FAIL: level %d tip speed\n", i; bad = 1 }
  if (!(y1 >= 0.19)) { print "FAIL: the level-1 primary crack does not reach the top edge"; bad = 1 }
  exit bad }'
