#!/usr/bin/env bash
# The execution model on glint-render's command line: a chain variant renders with the wavefront
# renderer by default and with the scalar one under --scalar; a variant without the wavefront
# renderer accepts --scalar and renders as always.
#
#   execution_model_test.bash CASE PROGRAM SCENE SCRATCH OTHER_PROGRAM [FORGE]
#
# CASE is one of the functions below named case_*; PROGRAM is glint-render (a chain variant),
# OTHER_PROGRAM a glint-render of a variant without the wavefront renderer (glint-render-report),
# FORGE glint-checkpoint-forge (tests/cli/checkpoint_forge.cpp).
# Each runs in the empty directory SCRATCH in a second or so. Exit status 0 on success, 1 on a
# failure, with the reason on stderr.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
case_name=$1 program=$2 scene=$3 scratch=$4 other_program=$5 forge=${6:-}

enter_scratch "$scratch"

# The mean of a PFM's values, after checking that it is WIDTH x HEIGHT RGB and every value is
# finite.
pfm_mean() { # FILE WIDTH HEIGHT
  local header="PF
$2 $3
-1.0
"
  [[ $(head -c ${#header} "$1") == "${header%$'\n'}" ]] || fail "$1 is not a $2x$3 PFM"
  tail -c +$((${#header} + 1)) "$1" | od -An -v -tf4 |
    awk -v expected=$(($2 * $3 * 3)) -v file="$1" '
      { for (i = 1; i <= NF; i++) { if (tolower($i) ~ /nan|inf/) bad++; sum += $i; n++ } }
      END {
        if (n != expected) { printf "%s holds %d values, not %d\n", file, n, expected > "/dev/stderr"; exit 1 }
        if (bad) { printf "%s holds %d values that are not finite\n", file, bad > "/dev/stderr"; exit 1 }
        printf "%.9g\n", sum / n
      }' || fail "$1 is not a complete image of finite values"
}

summary_names() { # MODEL: the summary line names the variant and MODEL (then the SIMD set)
  grep -Eq "^glint-render(-[a-z-]+)? \([a-z_]+, $1, [a-z0-9]+, [a-z0-9 ]+\): " err.log ||
    fail "the summary line does not name the $1 renderer"
}

# --scalar renders a complete image of finite values, of the size asked for.
case_scalar_renders() {
  "$program" "$scene" --scalar --width 40 --height 30 --spp 4 -o out.png --hdr out.pfm \
    2>err.log || fail "exit status $?"
  summary_names scalar
  [[ -f out.png ]] || fail "no PNG written"
  pfm_mean out.pfm 40 30 >/dev/null
}

# Both execution models render the scene, and their images agree statistically: the same mean
# radiance within 1% at 48x32 pixels and 64 spp (about 98,000 samples each; renders with other
# seeds differ by about 0.1% there, so this is no test of luck, while a bias of a percent
# fails). That they are the same bit for bit, resume_across_models checks.
case_models_agree() {
  local options=(--width 48 --height 32 --spp 64 --max-depth 6 --threads 2)
  "$program" "$scene" "${options[@]}" -o wavefront.png --hdr wavefront.pfm 2>err.log ||
    fail "the default (wavefront) render failed: status $?"
  summary_names wavefront
  "$program" "$scene" "${options[@]}" --scalar -o scalar.png --hdr scalar.pfm 2>err.log ||
    fail "the --scalar render failed: status $?"
  summary_names scalar
  local wavefront scalar
  wavefront=$(pfm_mean wavefront.pfm 48 32) || exit 1
  scalar=$(pfm_mean scalar.pfm 48 32) || exit 1
  awk -v w="$wavefront" -v s="$scalar" 'BEGIN { exit !(s > 0 && w / s > 0.99 && w / s < 1.01) }' ||
    fail "mean radiance $wavefront (wavefront) against $scalar (scalar): more than 1% apart"
}

# The two execution models give the same sums bit for bit, so a checkpoint of either continues
# with either: half rendered with --scalar and resumed without it, and the other way round, the
# bytes of an uninterrupted render. A checkpoint that names the wavefront renderer in its variant
# ("NAME, wavefront", as older ones did; made with FORGE, glint-checkpoint-forge) resumes too.
case_resume_across_models() {
  local options=(--width 40 --height 30 --spp 64 --max-depth 3 -o out.png --hdr out.pfm)
  "$program" "$scene" "${options[@]}" --quiet -o full.png --hdr full.pfm ||
    fail "the uninterrupted render failed (status $?)"
  "$program" "$scene" "${options[@]}" --scalar --time-limit 0 --checkpoint scalar.ck --quiet ||
    fail "making the scalar checkpoint failed (status $?)"
  "$program" "$scene" "${options[@]}" --time-limit 0 --checkpoint wavefront.ck --quiet ||
    fail "making the wavefront checkpoint failed (status $?)"
  cmp -s scalar.ck wavefront.ck || fail "the two execution models wrote different checkpoints"
  local variant
  variant=$("$program" --help | sed -n 's/^variant: \([a-z0-9_]*\).*/\1/p')
  "$forge" scalar.ck legacy.ck "$variant, wavefront" || fail "forging the legacy checkpoint failed"
  local resume
  for resume in "--resume scalar.ck" "--scalar --resume wavefront.ck" "--resume legacy.ck" \
    "--scalar --resume legacy.ck"; do
    rm -f out.png out.pfm
    # shellcheck disable=SC2086  # the options are words
    "$program" "$scene" "${options[@]}" $resume 2>err.log || fail "$resume: exit status $?"
    cmp out.pfm full.pfm || fail "$resume: the PFM differs from the uninterrupted render's"
    cmp out.png full.png || fail "$resume: the PNG differs from the uninterrupted render's"
  done
}

# A checkpoint whose variant name holds a newline and a terminal escape sequence (anyone may
# write the file): refused, with the name escaped on one line, no control byte printed.
case_forged_variant() {
  local options=(--width 40 --height 30 --spp 64 --max-depth 3 -o out.png)
  "$program" "$scene" "${options[@]}" --time-limit 0 --checkpoint made.ck --quiet ||
    fail "making the checkpoint failed (status $?)"
  "$forge" made.ck forged.ck $'fast\n\e[31mred\\' || fail "forging the checkpoint failed"
  rm -f out.png
  "$program" "$scene" "${options[@]}" --resume forged.ck 2>err.log
  local status=$?
  ((status == 1)) || fail "exit status $status, expected 1"
  [[ $(cat err.log) == "glint-render: error: cannot resume from forged.ck: it was made by variant 'fast\x0a\x1b[31mred\x5c', this is variant '"*"'" ]] ||
    fail "the message does not show the name escaped"
  ! LC_ALL=C grep -q $'\e' err.log || fail "an escape byte reached stderr"
  [[ ! -e out.png ]] || fail "an image was written"
}

# A variant without the wavefront renderer: --scalar is accepted and changes nothing, and its
# summary says scalar either way.
case_scalar_changes_nothing() {
  local options=(--width 24 --height 16 --spp 4 --max-depth 3)
  "$other_program" "$scene" "${options[@]}" -o plain.png --hdr plain.pfm 2>err.log ||
    fail "exit status $?"
  summary_names scalar
  "$other_program" "$scene" "${options[@]}" --scalar -o scalar.png --hdr scalar.pfm 2>err.log ||
    fail "with --scalar: exit status $?"
  summary_names scalar
  cmp plain.pfm scalar.pfm || fail "--scalar changed the image"
}

run_case "$case_name"
