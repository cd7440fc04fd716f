#!/usr/bin/env bash
# glint-render's instruction sets (--simd): the same image bit for bit with each set this CPU
# runs, at 1, 2 and 5 threads and with --scalar; the summary line naming the set; on emulated
# CPUs (QEMU's user mode) without AVX-512 and without AVX2, the widest set they have chosen by
# itself, the same image again, and a set the CPU lacks refused.
#
#   simd_test.bash CASE PROGRAM SCENE SCRATCH [QEMU]
#
# CASE is one of the functions below named case_*; PROGRAM is glint-render, SCENE a scene to
# render (the test renders it at 32x24, 4 samples per pixel), QEMU the qemu-x86_64 emulator
# for the emulated cases. Runs in the empty directory SCRATCH. Exit status 0 on success, 1 on a
# failure, with the reason on stderr.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
case_name=$1 program=$2 scene=$3 scratch=$4 qemu=${5:-}

enter_scratch "$scratch"

# Renders SCENE to NAME.pfm with the given options (and the launcher of $launcher, if any);
# fails unless it succeeds and the summary line names SET.
render() { # NAME SET OPTION...
  local name=$1 set=$2
  shift 2
  ${launcher:-} "$program" "$scene" --width 32 --height 24 --spp 4 -o "$name.png" \
    --hdr "$name.pfm" "$@" 2>err.log || fail "$name: exit status $?"
  grep -Eq "^glint-render \([^)]*, $set, (one path at a time|[0-9]+ paths at once)\)" err.log ||
    fail "$name: the summary line does not name the instruction set $set"
}

same_bytes() { # REFERENCE FILE...
  local reference=$1
  shift
  for file in "$@"; do
    cmp -s "$reference" "$file" || fail "$file differs from $reference"
  done
}

# The sets --help lists, and the one auto takes on this CPU.
sets_line=$("$program" --help | grep '^instruction sets (--simd): ') ||
  fail "--help does not list the instruction sets"
auto_set=$(sed -E 's/.*\(auto: ([a-z0-9]+) on this CPU\)$/\1/' <<<"$sets_line")
read -ra listed_sets <<<"$(sed -E 's/^instruction sets \(--simd\): (.*) \(auto:.*/\1/; s/,//g' <<<"$sets_line")"

case_same_image() {
  local runs=() set threads
  [[ " ${listed_sets[*]} " == *" scalar avx2 avx512 "* ]] ||
    fail "glint-render lists '${listed_sets[*]}', not scalar, avx2 and avx512"
  render auto "$auto_set" --threads 2
  # The sets are listed narrowest first; this CPU runs those up to auto's.
  for set in "${listed_sets[@]}"; do
    for threads in 1 2 5; do
      render "$set-$threads" "$set" --simd "$set" --threads "$threads"
      runs+=("$set-$threads.pfm")
    done
    render "$set-one-path" "$set" --simd "$set" --scalar --threads 3
    runs+=("$set-one-path.pfm")
    [[ $set == "$auto_set" ]] && break
  done
  ((${#runs[@]} >= 4)) || fail "only ${#runs[@]} renders compared"
  same_bytes auto.pfm "${runs[@]}"
}

# Under emulation: the emulated CPU's widest set, chosen by auto, and the native image.
emulated_same_image() { # CPU SET
  render native "$auto_set" --threads 2
  launcher="$qemu -cpu $1" render emulated "$2" --threads 2
  same_bytes native.pfm emulated.pfm
}

case_emulated_without_avx2() { emulated_same_image Nehalem scalar; }
case_emulated_without_avx512() { emulated_same_image Haswell avx2; }

case_emulated_lacking_set() {
  "$qemu" -cpu Haswell "$program" "$scene" --simd avx512 -o out.png 2>err.log
  local status=$?
  ((status == 2)) || fail "--simd avx512 on an emulated Haswell: status $status, not 2"
  grep -q -- "--simd avx512: this CPU lacks the instruction set" err.log ||
    fail "the message does not say that the CPU lacks the set"
  [[ ! -e out.png ]] || fail "an image was written"
}

run_case "$case_name"
echo "ok ($case_name)"
