#!/usr/bin/env bash
# `check` forecasts what the automatic triggers refine before the first crack (an elastic run of
# the coarse grid): the Brazilian disk, stretched near its strength over most of its area, is
# warned about; the plate with a hole, whose stretch peaks at the hole, is not.
set -u
bin="$1"; decks="$2"; fail=0
expect() {  # deck, want warning (1/0)
  out=$("$bin" check "$decks/$1" 2>&1); rc=$?
  line=$(grep "^forecast" <<< "$out")
  if [[ $rc -ne 0 || -z $line ]]; then echo "FAIL $1: exit $rc, no forecast: $out"; fail=1; return; fi
  if grep -q "refine most of the body" <<< "$out"; then got=1; else got=0; fi
  if [[ $got -ne $2 ]]; then echo "FAIL $1: warning $got, want $2: $line"; fail=1; return; fi
  echo "ok   $1: $line"
}
expect brazilian_disk_pmb.yaml 1
expect plate_hole_pmb.yaml 0
# The profile's triggers are spelled out, the stretch trigger's reach once the body cracks included.
out=$("$bin" check "$decks/plate_hole_pmb.yaml" 2>&1)
if grep -q "^adapt .*0.5 x the children's critical stretch (once cracked, within 2 horizons of a crack) and damage growth" <<< "$out"; then
  echo "ok   plate_hole_pmb.yaml: $(grep '^adapt' <<< "$out")"
else
  echo "FAIL plate_hole_pmb.yaml: the adapt line does not name the reach: $(grep '^adapt' <<< "$out")"; fail=1
fi
exit $fail
