#!/usr/bin/env bash
# glint-render's estimators (--estimator, or chosen from the scene or the resumed checkpoint).
#
#   estimator_test.bash CASE PROGRAM APPS SCENE SCRATCH
#
# CASE is one of the functions below named case_*; PROGRAM is glint-render, APPS the folder of
# the variants' own programs (glint-render-NAME), SCENE a scene with a point light and glass
# (tiny.scene), which glint-render gives to vertex merging. Each runs in the empty directory
# SCRATCH in a second or so. Exit status 0 on success, 1 on a failure, with the reason on stderr.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
case_name=$1 program=$2 apps=$3 scene=$4 scratch=$5

enter_scratch "$scratch"
settings=(--width 24 --height 16 --spp 8 --max-depth 4 --seed 5)
options=("${settings[@]}" --quiet)

# The estimators glint-render holds, from its help: "--estimator NAME ... auto (...), A, B or C;".
held_estimators() {
  "$program" --help | tr '\n' ' ' | sed -E 's/ +/ /g' |
    sed -nE 's/.*--estimator NAME [^;]*\), ([a-z, -]+);.*/\1/p' | sed -E 's/,| or / /g'
}

# Each estimator renders the bytes of its own program, glint-render-NAME.
case_same_bytes_as_own_program() {
  local names name
  names=$(held_estimators)
  [[ -n $names ]] || fail "glint-render --help names no estimators"
  for name in $names; do
    [[ -x $apps/glint-render-$name ]] || fail "no program glint-render-$name"
    "$program" "$scene" "${options[@]}" --estimator "$name" -o a.png --hdr a.pfm 2>err.log ||
      fail "--estimator $name: exit status $?"
    "$apps/glint-render-$name" "$scene" "${options[@]}" -o b.png --hdr b.pfm 2>err.log ||
      fail "glint-render-$name: exit status $?"
    cmp -s a.pfm b.pfm && cmp -s a.png b.png ||
      fail "--estimator $name differs from glint-render-$name"
  done
}

# Without --estimator, a resumed render continues with the estimator that made its checkpoint,
# not the one the scene would choose: the bytes of an uninterrupted render with that estimator.
case_resume_follows_checkpoint() {
  local default
  default=$(held_estimators | awk '{ print $1 }')
  "$program" "$scene" "${options[@]}" --estimator "$default" -o full.png --hdr full.pfm ||
    fail "the uninterrupted render failed (status $?)"
  "$program" "$scene" "${options[@]}" --estimator "$default" --time-limit 0 \
    --checkpoint ck.glint -o out.png 2>err.log || fail "making the checkpoint failed (status $?)"
  rm -f out.png
  "$program" "$scene" "${settings[@]}" --resume ck.glint -o out.png --hdr out.pfm 2>err.log ||
    fail "resuming failed (status $?)"
  grep -q "^glint-render ($default, " err.log || fail "the summary does not name $default"
  cmp -s out.pfm full.pfm && cmp -s out.png full.png ||
    fail "the resumed image differs from the uninterrupted render's"
}

run_case "$case_name"
