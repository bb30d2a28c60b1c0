#!/usr/bin/env bash
# Runs the dynamic-fracture studies of the PhD thesis (ch. 6) and writes a Markdown report with
# our numbers beside the published ones, damage pictures, tip-speed CSVs and plots:
#   out/report/README.md
# Crack branching 6.1: uniform level 0 (1 mm), uniform level 1 (0.5 mm), adaptive 0 -> 1; beyond the
# thesis, adaptive 0 -> 2 against uniform level 2 (0.25 mm);
# Kalthoff-Winkler 6.2: adaptive level 1, level 2 and the energy trigger alone at both levels; 3D branching (end
# of 6.1): adaptive level 1. Both 2D branching studies also at the printed 22 MPa. Plate with a
# hole 6.3: models A, B, C (h = 15, 10, 5 mm). Grid orientation (ch. 5): uniform m = 3 on grids
# turned 0-40 deg, LPS, m = 5-7 references, AGRS (m- and delta-m-convergence) on 5-40 deg grids.
# Usage: scripts/fracture-report.sh [OUT] (about 25 min on 2 cores, 11 of them the uniform 0.5 mm
# m = 6 grid-orientation reference).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/report}"
[[ -x build/periadapt ]] || { bash scripts/install-deps.sh; bash scripts/build.sh; }
mkdir -p "$out" "$out/timing"
# Level-0 uniform deck: the adaptive deck without its adapt section.
sed '/^adapt:/,/^  check_every:/d; /multirate: true/d' examples/crack_branching_2d_adaptive.yaml > "$out/crack_branching_2d_level0.yaml"
# The adaptive run with every node on the thesis' 50 ns (single-rate AGRS, as in the thesis).
sed '/multirate: true/d' examples/crack_branching_2d_adaptive.yaml > "$out/crack_branching_2d_adaptive_single_rate.yaml"
# The same three at the load the thesis prints (22 MPa; the examples use 14 MPa, see the decks).
for d in crack_branching_2d_level0:"$out/crack_branching_2d_level0.yaml" \
         crack_branching_2d:examples/crack_branching_2d.yaml \
         crack_branching_2d_adaptive:examples/crack_branching_2d_adaptive.yaml; do
  sed 's/14\.0e6/22.0e6/' "${d#*:}" > "$out/${d%%:*}_22MPa.yaml"
done
run() {  # name deck
  echo "running $1 ..."
  ./build/periadapt run "$2" --out "$out/$1" --quiet > "$out/$1.log" 2>&1 || { cat "$out/$1.log"; exit 1; }
}
run branching_L0 "$out/crack_branching_2d_level0.yaml"
run branching_L1 examples/crack_branching_2d.yaml
run branching_adaptive examples/crack_branching_2d_adaptive.yaml
run branching_adaptive_1rate "$out/crack_branching_2d_adaptive_single_rate.yaml"
# Wall-time ratios from five more alternating runs of each (the smallest time of each counts:
# the VM's noise only ever adds time).
for k in 1 2 3 4 5; do
  run "timing/L1_$k" examples/crack_branching_2d.yaml
  run "timing/adaptive_$k" examples/crack_branching_2d_adaptive.yaml
  run "timing/adaptive_1rate_$k" "$out/crack_branching_2d_adaptive_single_rate.yaml"
done
# Beyond the thesis: AGRS over two levels (four-rate and single-rate stepping) against the uniform
# level-2 grid.
sed '/multirate: true/d; /multirate_ratio/d' examples/crack_branching_2d_adaptive_L2.yaml \
  > "$out/crack_branching_2d_adaptive_L2_single_rate.yaml"
run branching_L2 examples/crack_branching_2d_L2.yaml
run branching_adaptive_L2 examples/crack_branching_2d_adaptive_L2.yaml
run branching_adaptive_L2_1rate "$out/crack_branching_2d_adaptive_L2_single_rate.yaml"
run branching_L0_22MPa "$out/crack_branching_2d_level0_22MPa.yaml"
run branching_L1_22MPa "$out/crack_branching_2d_22MPa.yaml"
run branching_adaptive_22MPa "$out/crack_branching_2d_adaptive_22MPa.yaml"
run kalthoff_winkler examples/kalthoff_winkler_2d_adaptive.yaml
# Level 2 (dt halved for the finer level's stable step, 54 us as in the thesis) and the energy
# trigger alone at 0.3 W_max.
sed 's/max_level: 1/max_level: 2/; s/time_step: 70.0e-9/time_step: 35.0e-9/; s/end_time: 90.0e-6/end_time: 54.0e-6/' \
  examples/kalthoff_winkler_2d_adaptive.yaml > "$out/kalthoff_winkler_level2.yaml"
sed '/damage_trigger: true/d; s/energy_trigger: 0.7/energy_trigger: 0.3/' \
  examples/kalthoff_winkler_2d_adaptive.yaml > "$out/kalthoff_winkler_energy_only.yaml"
sed '/damage_trigger: true/d; s/energy_trigger: 0.7/energy_trigger: 0.3/' \
  "$out/kalthoff_winkler_level2.yaml" > "$out/kalthoff_winkler_energy_only_level2.yaml"
run kalthoff_winkler_L2 "$out/kalthoff_winkler_level2.yaml"
run kalthoff_winkler_energy "$out/kalthoff_winkler_energy_only.yaml"
run kalthoff_winkler_energy_L2 "$out/kalthoff_winkler_energy_only_level2.yaml"
run branching_3d examples/crack_branching_3d_adaptive.yaml
sed '/multirate: true/d; /multirate_ratio/d' examples/crack_branching_3d_adaptive.yaml > "$out/crack_branching_3d_single_rate.yaml"
run branching_3d_1rate "$out/crack_branching_3d_single_rate.yaml"
# Plate with a hole 6.3: model C is the example deck (h = 5 mm, 28 MPa); B and A move the
# pre-crack 10 and 15 mm below the hole with the thesis' loads and start times.
sed 's/0\.019\]/0.014]/g; s/28\.0e6/26.0e6/; s/start_time: 1.92e-6/start_time: 1.80e-6/' \
  examples/plate_with_hole_2d_adaptive.yaml > "$out/plate_with_hole_B.yaml"
sed 's/0\.019\]/0.009]/g; s/28\.0e6/22.0e6/' examples/plate_with_hole_2d_adaptive.yaml > "$out/plate_with_hole_A.yaml"
run plate_hole_C examples/plate_with_hole_2d_adaptive.yaml
run plate_hole_B "$out/plate_with_hole_B.yaml"
run plate_hole_A "$out/plate_with_hole_A.yaml"
# Grid orientation, thesis ch. 5: uniform m = 3 on rotated grids (the printed 0.8 MPa, 560 us),
# the 10 deg grid quasi-statically (3 ms ramp to 3 MPa), uniform m = 6 / 7 references and AGRS
# raising m near the crack (Table 5.1), and the weak bond directions (5.2).
for a in 0 5 10 20 30 40; do
  sed -e "s/rotation_deg: 0.0/rotation_deg: $a/" examples/grid_orientation_pmb.yaml > "$out/grid_m3_$a.yaml"
  run "grid_m3_$a" "$out/grid_m3_$a.yaml"
done
sed -e 's/value: \[0.0, 0.8e6\]/value: [0.0, 0.0]/' -e 's/value: \[0.0, -0.8e6\]/value: [0.0, 0.0]/' \
    -e 's/rotation_deg: 0.0/rotation_deg: 10/' -e 's/end_time: 560.0e-6/end_time: 3.0e-3/' \
    -e 's/history_every: 20/history_every: 200/' examples/grid_orientation_pmb.yaml \
  | sed -e '/name: top/,/value/ s/value: \[0.0, 0.0\]/value: [0.0, 3.0e6]\n    time: {function: ramp, start: 0.0, end: 3.0e-3}/' \
        -e '/name: bottom/,/value/ s/value: \[0.0, 0.0\]/value: [0.0, -3.0e6]\n    time: {function: ramp, start: 0.0, end: 3.0e-3}/' \
  > "$out/grid_m3_10_quasistatic.yaml"
run grid_m3_10_quasistatic "$out/grid_m3_10_quasistatic.yaml"
uniform_of() {  # adaptive deck -> the uniform 1 mm grid with the refined level's m
  sed -e '/^adapt:/,/^  check_every:/d' -e 's/spacing: 2.0e-3/spacing: 1.0e-3/' -e "s/horizon_factor: [0-9.]*/horizon_factor: $1/"
}
uniform_of 6 < examples/grid_orientation_adaptive.yaml > "$out/grid_m6_10.yaml"
uniform_of 5 < examples/grid_orientation_adaptive.yaml > "$out/grid_m5_10.yaml"
# The state-based (LPS) material on the 10 and 40 deg grids (thesis Fig. 5.3c-d, 0.7 MPa).
for a in 10 40; do
  sed "s/rotation_deg: 0.0/rotation_deg: $a/" examples/grid_orientation_lps.yaml > "$out/grid_lps_$a.yaml"
  run "grid_lps_$a" "$out/grid_lps_$a.yaml"
done
run grid_m5_10 "$out/grid_m5_10.yaml"
sed -e 's/rotation_deg: 10.0/rotation_deg: 5.0/' -e 's/horizon_factor: 3.0/horizon_factor: 3.5/' \
  examples/grid_orientation_adaptive.yaml > "$out/grid_adaptive_5.yaml"
uniform_of 7 < "$out/grid_adaptive_5.yaml" > "$out/grid_m7_5.yaml"
run grid_m6_10 "$out/grid_m6_10.yaml"
run grid_adaptive_10 examples/grid_orientation_adaptive.yaml
run grid_m7_5 "$out/grid_m7_5.yaml"
run grid_adaptive_5 "$out/grid_adaptive_5.yaml"
# The thesis runs AGRS on the 5 and 10 deg grids only; the same m-convergence deck on the other
# rotated grids of the study.
for a in 20 30 40; do
  sed "s/rotation_deg: 10.0/rotation_deg: $a/" examples/grid_orientation_adaptive.yaml > "$out/grid_adaptive_$a.yaml"
  run "grid_adaptive_$a" "$out/grid_adaptive_$a.yaml"
done
# delta-m, two levels (Table 5.1 third row, Fig. 5.17) against the uniform 0.5 mm, m = 6 grid.
sed -e '/^adapt:/,/^  check_every:/d' -e 's/spacing: 2.0e-3/spacing: 0.5e-3/' -e 's/horizon_factor: 3.0/horizon_factor: 6.0/' \
  examples/grid_orientation_adaptive_dm.yaml > "$out/grid_m6_05_10.yaml"
run grid_m6_05_10 "$out/grid_m6_05_10.yaml"
run grid_adaptive_dm_10 examples/grid_orientation_adaptive_dm.yaml
./build/periadapt study weak-directions --out "$out/weak_directions" > "$out/weak_directions.txt"
num() {  # summary key -> value (first match), "-" when null or absent
  local v
  v=$(grep -m1 "\"$2\"" "$out/$1/summary.json" | sed -E 's/.*: *//; s/,$//')
  [[ -z "$v" || "$v" == null ]] && echo "-" || echo "$v"
}
# Markdown images of a run's damage pictures.
pictures() { for p in "$out/$1"/damage_*.png; do echo "![$(basename "$p")]($1/$(basename "$p"))"; done; }
us() { [[ "$1" == "-" ]] && echo "-" || awk -v t="$1" 'BEGIN { printf "%.2f", t * 1e6 }'; }
mm() { [[ "$1" == "-" ]] && echo "-" || awk -v t="$1" 'BEGIN { printf "%.1f", t * 1e3 }'; }
f0() { [[ "$1" == "-" ]] && echo "-" || awk -v t="$1" 'BEGIN { printf "%.0f", t }'; }
f2() { [[ "$1" == "-" ]] && echo "-" || awk -v t="$1" 'BEGIN { printf "%.2f", t }'; }
row() {  # name label published...
  local n=$1
  echo "| $2 | $(num "$n" final) | $(us "$(num "$n" first_advance_time_s)") / $(us "$(num "$n" initiation_time_s)") | $(us "$(num "$n" branching_time_s)") | $(mm "$(num "$n" branch_length_m)") | $(f0 "$(num "$n" mean_speed_m_s)") | $(mm "$(num "$n" branch_asymmetry_m)") | $(f2 "$(num "$n" wall_time_s)") | $3 |"
}
{
  echo "# PeriAdapt fracture report"
  echo
  echo "Generated $(date -u +%Y-%m-%dT%H:%MZ) on $(nproc) cores by \`scripts/fracture-report.sh\`."
  echo
  echo "## Crack branching, soda-lime glass (thesis 6.1, Tables 6.2-6.4)"
  echo
  echo "| run | nodes (final) | t_i (us): tip past the pre-crack / one spacing past | t_b (us) | l_b (mm, from the pre-crack tip) | mean tip speed (m/s) | branch asymmetry (mm) | wall (s) | published: nodes, t_i, t_b, l_b, speed |"
  echo "|---|---|---|---|---|---|---|---|---|"
  row branching_L0 "uniform level 0 (1 mm)" "4,000, 6.05, 21.85, 17.0, 1,319"
  row branching_L1 "uniform level 1 (0.5 mm)" "16,000, 6.00, 20.85, 15.0, 1,344"
  row branching_adaptive "adaptive 0 -> 1 (two-rate stepping)" "4,000-6,293, 6.00, 21.83, 16.5, 1,308"
  row branching_adaptive_1rate "adaptive 0 -> 1 (single rate, as the thesis)" "4,000-6,293, 6.00, 21.83, 16.5, 1,308"
  row branching_L0_22MPa "uniform level 0, printed 22 MPa" "as above"
  row branching_L1_22MPa "uniform level 1, printed 22 MPa" "as above"
  row branching_adaptive_22MPa "adaptive, printed 22 MPa" "as above"
  echo
  echo "The examples load the plate with 14 MPa: at the 22 MPa printed in the thesis, with its own grid parameters (Table 6.1), the 1 mm grid cracks away from the tip and the 0.5 mm crack branches after a few mm (rows above; pictures at the end of this section)."
  echo
  echo "t_i: the thesis defines the tip as the farthest node with damage > 0.35 and t_i as the time the crack starts propagating; the first number is the first time such a node lies past the pre-crack end, the second the time it is one grid spacing past (our stricter default, summary.json initiation_time_s). t_b and l_b: the fork, where the crack splits into two bands of cracked nodes (traced back from the first cross-section in which the branches lie more than one coarse horizon apart, summary.json branch_separation_*), and the time the tip passed it. Branch asymmetry: the Hausdorff distance between the cracked nodes above the crack line and the mirror images of those below it, at the end time."
  echo
  best() { for k in 1 2 3 4 5; do num "timing/$1_$k" wall_time_s; done | sort -g | head -1; }
  tl1=$(best L1); ta=$(best adaptive); ta1=$(best adaptive_1rate)
  echo "Wall time, smallest of five alternating runs each: uniform level 1 $(f2 "$tl1") s, adaptive $(f2 "$ta") s (two-rate) and $(f2 "$ta1") s (single rate). Adaptive / uniform level 1: $(awk -v a="$ta" -v u="$tl1" 'BEGIN { printf "%.2f", a / u }') two-rate, $(awk -v a="$ta1" -v u="$tl1" 'BEGIN { printf "%.2f", a / u }') single rate (thesis 0.36, single rate). Bond evaluations adaptive / uniform level 1: $(awk -v a="$(num branching_adaptive bond_evaluations)" -v u="$(num branching_L1 bond_evaluations)" 'BEGIN { printf "%.3f", a / u }') two-rate, $(awk -v a="$(num branching_adaptive_1rate bond_evaluations)" -v u="$(num branching_L1 bond_evaluations)" 'BEGIN { printf "%.3f", a / u }') single rate. Two-rate stepping (solver.multirate): nodes whose own stable step allows 2 dt (here the level-0 nodes) take it, the refined ones the thesis' 50 ns. The adaptive runs use the interface-horizon correction (adapt.interface_horizon, Table 6.1): with method B children the interface horizon is 2.37 mm (Table 6.1: 2.10, method A)."
  echo
  echo "### Beyond the thesis: AGRS 0 -> 2"
  echo
  echo "The thesis refines this benchmark by one level. [crack_branching_2d_adaptive_L2.yaml](../../examples/crack_branching_2d_adaptive_L2.yaml) goes to level 2 (0.25 mm, delta 0.75 mm, dt 25 ns) with the pre-crack tip refined from the start, against the uniform 0.25 mm grid ([crack_branching_2d_L2.yaml](../../examples/crack_branching_2d_L2.yaml), 64,000 nodes). Four-rate stepping (multirate_ratio: 4): each node takes the longest of 1-4 dt its own stable step allows."
  echo
  echo "| run | nodes (final) | t_i (us) | t_b (us) | l_b (mm) | mean tip speed (m/s) | branch asymmetry (mm) | wall (s) | published |"
  echo "|---|---|---|---|---|---|---|---|---|"
  row branching_L2 "uniform level 2 (0.25 mm)" "- (not in the thesis)"
  row branching_adaptive_L2 "adaptive 0 -> 2 (four-rate stepping)" "-"
  row branching_adaptive_L2_1rate "adaptive 0 -> 2 (single rate)" "-"
  echo
  echo "Adaptive / uniform level 2: wall $(awk -v a="$(num branching_adaptive_L2 wall_time_s)" -v u="$(num branching_L2 wall_time_s)" 'BEGIN { printf "%.2f", a / u }') four-rate, $(awk -v a="$(num branching_adaptive_L2_1rate wall_time_s)" -v u="$(num branching_L2 wall_time_s)" 'BEGIN { printf "%.2f", a / u }') single rate (one run each); bond evaluations $(awk -v a="$(num branching_adaptive_L2 bond_evaluations)" -v u="$(num branching_L2 bond_evaluations)" 'BEGIN { printf "%.3f", a / u }') and $(awk -v a="$(num branching_adaptive_L2_1rate bond_evaluations)" -v u="$(num branching_L2 bond_evaluations)" 'BEGIN { printf "%.3f", a / u }')."
  echo
  for n in branching_L0 branching_L1 branching_adaptive branching_adaptive_1rate branching_L2 branching_adaptive_L2 branching_adaptive_L2_1rate branching_L0_22MPa branching_L1_22MPa branching_adaptive_22MPa; do
    echo "### $n"
    echo
    pictures "$n"
    echo
    echo "Tip speed: [$n/crack_speed.csv]($n/crack_speed.csv) ![speed]($n/crack_speed.png)"
    echo
  done
  echo "## Kalthoff-Winkler (thesis 6.2)"
  echo
  echo "| run | nodes (final) | children created | refined nodes > 1 coarse horizon from a crack | cracked nodes left coarse | t_i (us): tip past the notch / one spacing past | path angle (deg) | max tip speed (m/s) | final upper tip (mm) | wall (s) | published |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  kw() {  # name label published
    local tip
    tip=$(grep -m1 -A2 '"final_tip_m"' "$out/$1/summary.json" | tail -2 | tr -d ' \n' | awk -F, '{ printf "(%.1f, %.1f)", 1e3 * $1, 1e3 * $2 }')
    echo "| $2 | $(num "$1" final) | $(num "$1" nodes_added) | $(num "$1" refined_far_from_cracks) | $(num "$1" cracked_coarse_nodes) | $(us "$(num "$1" first_advance_time_s)") / $(us "$(num "$1" initiation_time_s)") | $(f2 "$(num "$1" path_angle_deg)") | $(f0 "$(num "$1" max_speed_m_s)") | $tip | $(f2 "$(num "$1" wall_time_s)") | $3 |"
  }
  kw kalthoff_winkler "level 1, energy 0.7 + damage" "5,000 + 4,453 nodes, t_i about 24 us, 68 deg, 1,981 m/s"
  kw kalthoff_winkler_L2 "level 2, energy 0.7 + damage" "5,000 + 6,902 nodes, about 68 deg"
  kw kalthoff_winkler_energy "level 1, energy 0.3 only" "a very large refined zone not interested by cracks; misses the secondary crack"
  kw kalthoff_winkler_energy_L2 "level 2, energy 0.3 only" "as level 1 (Fig. 6.11)"
  echo
  echo "The plate is 100 mm in the impact direction and 200 mm along the impacted edge (the standard specimen). The upper tip of a crack that runs through ends on the top edge (y = 200 mm) near x = 50 + 75 / tan(angle) mm. The energy trigger alone (Fig. 6.11) is judged as the thesis describes it: the refined nodes farther than one coarse horizon (6 mm) from every cracked node (damage > 0.35) are the zone 'not interested by cracks', the cracked nodes left on the coarse grid are what it misses. These runs, like the plate with a hole, go without the interface-horizon correction: with it the angles and speeds stay but the refined zones grow past the published counts (the deck comment gives the numbers)."
  echo
  for n in kalthoff_winkler kalthoff_winkler_L2 kalthoff_winkler_energy kalthoff_winkler_energy_L2; do
    echo "### $n"
    echo
    pictures "$n"
    echo
  done
  echo
  echo "## Crack branching 3D, Duran 50 glass (thesis 6.1, Fig. 6.5, level 1)"
  echo
  echo "| run | nodes (initial -> final) | t_i (us) | t_b (us) | mean tip speed (m/s) | bond evaluations | wall (s) | published |"
  echo "|---|---|---|---|---|---|---|---|"
  for n in branching_3d branching_3d_1rate; do
    label="four-rate stepping"; [[ $n == branching_3d_1rate ]] && label="single rate"
    echo "| $label | $(num $n initial) -> $(num $n final) | $(us "$(num $n initiation_time_s)") | $(us "$(num $n branching_time_s)") | $(f0 "$(num $n mean_speed_m_s)") | $(awk -v t="$(num $n bond_evaluations)" 'BEGIN { printf "%.0f M", t / 1e6 }') | $(f2 "$(num $n wall_time_s)") | 12,000 -> 26,644 nodes, branches (qualitative) |"
  done
  echo
  pictures branching_3d
  echo
  echo "## Pre-cracked plate with a hole (thesis 6.3, Figs. 6.12-6.14)"
  echo
  echo "Geometry (the thesis draws it only in a lost figure; ours matches its printed node count and loaded row): 30 x 44 mm, hole of 10 mm diameter centred at (20, 29) mm, bottom edge clamped, step traction on the top row, 10 mm pre-crack from the left edge h below the hole's lowest point. 1 mm grid, m = 3, level-1 AGRS (W >= 0.5 W_max and damage triggers), dt = 40 ns, 60 us."
  echo
  echo "| model | h (mm) | load (MPa) | nodes (initial -> final) | t_i (us) | closest approach of the tip to the hole (mm) | final tip (x, y mm) | outcome | published nodes |"
  echo "|---|---|---|---|---|---|---|---|---|"
  hole() {  # name h load published
    local c x y verdict
    c=$(num "$1" closest_approach_to_hole_m)
    x=$(grep -m1 -A1 '"final_tip_m"' "$out/$1/summary.json" | tail -1 | tr -d ' ,')
    y=$(grep -m1 -A2 '"final_tip_m"' "$out/$1/summary.json" | tail -1 | tr -d ' ,')
    verdict=$(awk -v c="$c" -v x="$x" 'BEGIN { if (c < 1e-3) print "reaches the hole"; else if (x >= 0.029) print "passes the hole"; else print "stops before the far edge" }')
    echo "| $1 | $2 | $3 | $(num "$1" initial) -> $(num "$1" final) | $(us "$(num "$1" initiation_time_s)") | $(mm "$c") | $(mm "$x"), $(mm "$y") | $verdict | $4 |"
  }
  hole plate_hole_C 5 28 "1,238 -> 2,522"
  hole plate_hole_B 10 26 "1,238 -> 2,340"
  hole plate_hole_A 15 22 "1,238 -> 1,860"
  echo
  echo "Thesis: the crack is drawn into the hole for the smallest h and passes it for the largest (Fig. 6.13, as in DYNA3D, Fig. 6.14). Here the hole also cracks from its sides (a 10 mm hole in a 30 mm plate under a step load), which the refinement follows: more refined nodes than published."
  echo
  for n in plate_hole_C plate_hole_B plate_hole_A; do
    echo "### $n"
    echo
    pictures "$n"
    echo
  done
  echo "## Grid orientation (thesis ch. 5, Tables 5.1-5.2)"
  echo
  echo "Plate 0.25 x 0.25 m, 50 mm edge crack from the left edge at mid-height (the thesis' Fig. 5.1a is lost: the printed 0.8 MPa starts this crack, but not a central one of the same length, whose static G is 0.68 J/m^2 against G0 = 7), 0.8 MPa step, 560 us, IPA-Hybrid areas. Path angle: from the initial tip to its last position, from the horizontal."
  echo
  echo "| run | grid angle (deg) | dX0 (mm) | m | nodes (initial -> final) | path angle (deg) | wall (s) | thesis (Table 5.2: CPU h, crack) |"
  echo "|---|---|---|---|---|---|---|---|"
  go() {  # name angle dx m published
    echo "| $1 | $2 | $3 | $4 | $(num "$1" initial) -> $(num "$1" final) | $(f2 "$(num "$1" path_angle_deg)") | $(f2 "$(num "$1" wall_time_s)") | $5 |"
  }
  for a in 0 5 10 20 30 40; do
    pub="deviated"; [[ $a == 0 ]] && pub="horizontal"; [[ $a == 5 ]] && pub="0.83 h (1 mm), deviated"
    go "grid_m3_$a" "$a" 1 3 "$pub"
  done
  go grid_m3_10_quasistatic 10 1 3 "deviated (quasi-static, Fig. 5.7)"
  go grid_lps_10 10 1 "3 (LPS)" "deviated, like BB (Fig. 5.3c)"
  go grid_lps_40 40 1 "3 (LPS)" "deviated, like BB (Fig. 5.3d)"
  go grid_m5_10 10 1 5 "less deviated (Figs. 5.12-5.15: m about 6-7 gives horizontal cracks)"
  go grid_m6_10 10 1 6 "horizontal; 62,502 nodes (Fig. 5.16a)"
  go grid_adaptive_10 10 "2 -> 1" "3 -> 6 (m)" "horizontal; 15,600 -> 19,062 nodes (Fig. 5.16b)"
  go grid_m6_05_10 10 0.5 6 "16.09 h, horizontal; 250,002 nodes (Fig. 5.17a)"
  go grid_adaptive_dm_10 10 "2 -> 0.5" "3 -> 4.5 -> 6 (delta-m)" "3.52 h, horizontal; 15,600 -> 26,778 nodes (Fig. 5.17b)"
  go grid_m7_5 5 1 7 "2.90 h, horizontal"
  go grid_adaptive_5 5 "2 -> 1" "3.5 -> 7 (m)" "2.20 h, horizontal"
  for a in 20 30 40; do go "grid_adaptive_$a" "$a" "2 -> 1" "3 -> 6 (m)" "- (AGRS on 5 and 10 deg only)"; done
  echo
  ratio() { awk -v a="$(num "$1" "$3")" -v u="$(num "$2" "$3")" 'BEGIN { printf "%.2f", a / u }'; }
  echo "Adaptive / uniform: 10 deg m-convergence: nodes $(ratio grid_adaptive_10 grid_m6_10 final), wall $(ratio grid_adaptive_10 grid_m6_10 wall_time_s) (thesis: nodes 19,062 / 62,502 = 0.30); 10 deg delta-m: nodes $(ratio grid_adaptive_dm_10 grid_m6_05_10 final), wall $(ratio grid_adaptive_dm_10 grid_m6_05_10 wall_time_s) (thesis 26,778 / 250,002 = 0.11 nodes, 3.52 / 16.09 h = 0.22 wall); 5 deg: nodes $(ratio grid_adaptive_5 grid_m7_5 final), wall $(ratio grid_adaptive_5 grid_m7_5 wall_time_s) (thesis 2.20 / 2.90 h = 0.76); 20, 30, 40 deg m-convergence against the 10 deg uniform m = 6 grid (every rotated grid has 62,492-62,504 nodes): nodes $(ratio grid_adaptive_20 grid_m6_10 final), $(ratio grid_adaptive_30 grid_m6_10 final), $(ratio grid_adaptive_40 grid_m6_10 final)."
  echo
  echo "Weak (bond) directions, thesis 5.2 (\`periadapt study weak-directions\`; thesis for m = 3: 0, 18.435, 26.565, 30.964, 45, 59.036, 63.435, 71.565, 90):"
  echo
  echo '```'
  grep '^m = ' "$out/weak_directions.txt"
  echo '```'
  echo
  for n in grid_m3_10 grid_m3_10_quasistatic grid_lps_10 grid_m5_10 grid_m6_10 grid_adaptive_10 grid_m6_05_10 grid_adaptive_dm_10 grid_adaptive_5 grid_adaptive_20 grid_adaptive_30 grid_adaptive_40; do
    echo "### $n"
    echo
    pictures "$n"
    echo
  done
  echo "Published numbers: Dipasquale, PhD thesis (2016), Tables 6.2-6.5; see docs and the closing notes for the known differences."
} > "$out/README.md"
echo "report: $out/README.md"
