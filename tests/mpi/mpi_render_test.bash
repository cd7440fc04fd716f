#!/usr/bin/env bash
# glint-render-mpi's promises, run under mpirun:
#
#   mpi_render_test.bash CASE MPIEXEC MPI_PROGRAM PROGRAM DEFAULT SOURCE_DIR SCRATCH [ARGS...]
#
# CASE is one of the functions below named case_*; it runs MPI_PROGRAM (glint-render-mpi) under
# MPIEXEC and PROGRAM (glint-render) in the empty directory SCRATCH; ARGS go to the case.
# DEFAULT is the programs' default estimator (the path tracer), which the long render names. mpirun
# runs as root in CI: the caller sets OMPI_ALLOW_RUN_AS_ROOT and OMPI_ALLOW_RUN_AS_ROOT_CONFIRM.
# Ranks may outnumber the cores (--oversubscribe). Exit status 0 on success, 1 on a failure,
# with the reason on stderr.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
case_name=$1 mpiexec=$2 mpi_program=$3 program=$4 default_estimator=$5 source_dir=$6 scratch=$7
shift 7

enter_scratch "$scratch"

# Each rank may run anywhere (not bound to one core), as a rank with several threads needs.
mpirun_n() { # RANKS ARGS...
  local ranks=$1
  shift
  "$mpiexec" --oversubscribe --bind-to none -n "$ranks" "$@"
}

glint_render() {
  "$program" "$@"
}

no_temporaries() {
  local left
  left=$(find . -name '*glint-partial*' -print)
  [[ -z $left ]] || fail "temporaries left behind: $left"
}

# A room lit by a small lamp, with a mirror and a glass ball: tiles differ in cost. 13 samples
# per pixel: passes of 1, 1, 2, 4, 4 and 1 samples with at most 4 per pass.
lamp_room=$source_dir/bench/scenes/lamp-room.scene
small=(--width 72 --height 56 --spp 13 --max-depth 8 --seed 3)
# A point light above a glass ball above a floor, on black: glint-render chooses vertex merging
# for it, and every estimator renders it (light tracing needs the black background).
caustic=$source_dir/docs/images/glass-ball-caustic.scene

# The same bytes, PNG and PFM, as glint-render's, for RANKS ranks of THREADS threads each, the
# summary naming the variant that rendered (VARIANT: a pattern).
case_same_bytes() { # RANKS THREADS [OPTION...]: OPTIONs for both programs (--scalar, --simd)
  same_bytes_of "$lamp_room" "[a-z_]+" "$@"
}

# case_same_bytes of SCENE, whose summary names VARIANT.
same_bytes_of() { # SCENE VARIANT RANKS THREADS [OPTION...]
  local scene=$1 variant=$2 ranks=$3 threads=$4
  shift 4
  glint_render "$scene" "${small[@]}" "$@" -o one.png --hdr one.pfm --quiet ||
    fail "glint-render failed (status $?)"
  mpirun_n "$ranks" "$mpi_program" "$scene" "${small[@]}" "$@" --threads "$threads" \
    -o many.png --hdr many.pfm 2>err.log || fail "glint-render-mpi failed (status $?)"
  cmp one.png many.png || fail "the PNG differs from glint-render's"
  cmp one.pfm many.pfm || fail "the PFM differs from glint-render's"
  local model="[a-z]+" simd="[a-z0-9]+"
  [[ " $* " == *" --scalar "* ]] && model=scalar
  [[ " $* " == *" --simd scalar "* ]] && simd=scalar
  local name=${scene##*/}
  local summary="^glint-render-mpi \($variant, $model, $simd, (one path at a time|[0-9]+ paths at once)\): .*${name//./\\.} -> many\.png: 72x56, 13 spp, depth 8 in [0-9.]+ s on $ranks ranks? x $threads threads: "
  grep -Eq "$summary" err.log || fail "no summary line naming $variant on $ranks ranks x $threads threads"
  grep -Eq "^glint-render-mpi: idle: rank 0 [0-9.]+ s \([0-9]+%\)" err.log || fail "no idle line"
  no_temporaries
}

# A scene whose spheres show images: glint-render's bytes, every rank reading the images.
case_textured_same_bytes() { # RANKS THREADS
  same_bytes_of "$source_dir/bench/scenes/textured.scene" "[a-z_]+" "$@"
}

# Ranks that read different images for the same scene (each in its own directory, mpirun's
# A : B form) would mix two scenes into one image: refused, status 1, nothing written.
case_different_images() {
  mkdir -p a b
  "$program" "$lamp_room" --width 8 --height 4 --spp 1 -o a/map.png --quiet || fail "map: $?"
  "$program" "$lamp_room" --width 4 --height 2 --spp 1 -o b/map.png --quiet ||
    fail "map: $?"
  for dir in a b; do
    { cat "$lamp_room"; echo; echo "sphere center=0,0,-1000 radius=1 texture=map.png"; } \
      >$dir/textured.scene
  done
  for read in "" --scene-everywhere; do
    "$mpiexec" --oversubscribe --bind-to none -n 1 -wdir a "$mpi_program" textured.scene \
      "${small[@]}" --threads 1 -o "$PWD/out.png" $read : -n 1 -wdir b "$mpi_program" \
      textured.scene "${small[@]}" --threads 1 -o "$PWD/out.png" $read >out.log 2>err.log
    local status=$?
    ((status == 1)) || fail "exit status $status, expected 1 ($read)"
    grep -q "cannot render textured.scene: the images its spheres show differ here from rank 0's" \
      err.log || fail "no message naming the images ($read)"
    [[ ! -e out.png ]] || fail "an image was written ($read)"
  done
}

# Each estimator over MPI, on the caustic scene: glint-render's bytes, the splats of every rank
# summed (and, for vertex merging, every rank's own light phase of each sample index).
case_estimator_same_bytes() { # RANKS THREADS ESTIMATOR: a name, or auto (vcm, by the scene)
  local ranks=$1 threads=$2 estimator=$3
  local variant=${estimator//-/_}
  [[ $estimator == auto ]] && variant=vcm
  same_bytes_of "$caustic" "$variant" "$ranks" "$threads" --estimator "$estimator"
  if [[ $estimator != auto ]]; then
    grep -Eq "^glint-render-mpi: idle: .*, splats [0-9.]+ [kMG]?B summed$" err.log ||
      fail "the idle line does not say what the splats' sum took"
  fi
}

# A checkpoint of either program resumes under the other, to the uninterrupted bytes; both
# write the same checkpoint after the first pass. On the lamp room (the path tracer), or with
# "caustic" on the caustic scene: vertex merging, which splats and has a light phase, chosen
# again from the checkpoint when resumed.
case_resume_across() { # [caustic]
  local scene=$lamp_room
  [[ ${1:-} == caustic ]] && scene=$caustic
  local args=("$scene" "${small[@]}" --quiet)
  glint_render "${args[@]}" -o full.png --hdr full.pfm || fail "the full render failed"
  glint_render "${args[@]}" -o a.png --time-limit 0 --checkpoint one.ck || fail "glint-render: $?"
  mpirun_n 2 "$mpi_program" "${args[@]}" --threads 1 -o b.png --hdr b.pfm --resume one.ck \
    2>err.log || fail "glint-render-mpi --resume failed (status $?)"
  cmp b.png full.png && cmp b.pfm full.pfm || fail "glint-render's checkpoint resumed to other bytes"
  mpirun_n 3 "$mpi_program" "${args[@]}" --threads 1 -o c.png --time-limit 0 --checkpoint many.ck \
    2>err.log || fail "glint-render-mpi --checkpoint failed (status $?)"
  cmp one.ck many.ck || fail "the two programs' checkpoints after one pass differ"
  cmp a.png c.png || fail "the two programs' one-pass images differ"
  glint_render "${args[@]}" -o d.png --hdr d.pfm --resume many.ck 2>err.log ||
    fail "glint-render --resume failed (status $?)"
  cmp d.png full.png && cmp d.pfm full.pfm || fail "glint-render-mpi's checkpoint resumed to other bytes"
}

# A scene error met by every rank: one FILE:LINE: error: message, status 1, nothing written.
case_scene_error() {
  local scene=$source_dir/tests/cli/scenes/overlapping-glass.scene
  for read in "" --scene-everywhere; do
    mpirun_n 3 "$mpi_program" "$scene" -o out.png $read >out.log 2>err.log
    local status=$?
    ((status == 1)) || fail "exit status $status, expected 1 ($read)"
    local errors
    errors=$(grep -Ec "overlapping-glass\.scene:[0-9]+: error: transparent spheres" err.log)
    ((errors == 1)) || fail "$errors messages for the scene error, expected 1 ($read)"
    [[ ! -e out.png ]] || fail "an image was written"
  done
  mpirun_n 2 "$mpi_program" no-such.scene -o out.png 2>err.log
  local status=$?
  ((status == 1)) || fail "exit status $status for a missing scene, expected 1"
  (($(grep -c "^no-such\.scene: error: cannot open file" err.log) == 1)) ||
    fail "not one message for the missing scene"
}

# Ranks started with different image options (mpirun's A : B form) would mix two renders into
# one image: refused before rendering, with one message naming the difference, status 1. (The
# default variant has the wavefront renderer, so --scalar is a difference.)
case_different_settings() {
  local args=("$lamp_room" "${small[@]}" --threads 1 -o out.png)
  local other expected
  for other in "--seed 4" "--max-depth 2" "--spp 12" "--scalar" "--estimator vcm"; do
    case $other in
      --estimator*) expected="this rank has --estimator vcm, rank 0 has auto" ;;
      --seed*) expected="this rank has seed 4, rank 0 has 3" ;;
      --max-depth*) expected="this rank has max depth 2, rank 0 has 8" ;;
      --spp*) expected="this rank has samples per pixel 12, rank 0 has 13" ;;
      --scalar) expected="this rank renders with [a-z_]+, scalar, rank 0 with [a-z_]+, wavefront" ;;
    esac
    "$mpiexec" --oversubscribe --bind-to none -n 1 "$mpi_program" "${args[@]}" : \
      -n 1 "$mpi_program" "${args[@]}" $other >out.log 2>err.log
    local status=$?
    ((status == 1)) || fail "$other: exit status $status, expected 1"
    (($(grep -c "failed:" err.log) == 1)) || fail "$other: not one message"
    grep -Eq "^glint-render-mpi: rank 1 \(on .*\) failed:$" err.log || fail "$other: rank 1 not named"
    grep -Eq "^glint-render-mpi: error: $expected: every rank must be started with the same image options" err.log ||
      fail "$other: the difference is not named"
    ! grep -q elapsed err.log || fail "$other: the render started"
    [[ ! -e out.png ]] || fail "$other: an image was written"
  done
}

# A bad option: status 2, the message and the usage once.
case_bad_option() {
  mpirun_n 2 "$mpi_program" "$lamp_room" --frobnicate 2>err.log
  local status=$?
  ((status == 2)) || fail "exit status $status, expected 2"
  (($(grep -c "^glint-render-mpi: unknown option '--frobnicate'$" err.log) == 1)) ||
    fail "not one message for the option"
  (($(grep -c "^Run 'glint-render-mpi --help' for the options" err.log) == 1)) ||
    fail "not one pointer to --help"
}

# A render long enough to be stopped or killed while it runs: 37 passes of tiny.scene by the
# path tracer (about 4 s on 2 ranks of a Zen 5 with the wavefront renderer; at a quarter of the
# pixels it could end before the signal arrived).
long_render=("$source_dir/tests/cli/scenes/tiny.scene" --width 320 --height 240 --spp 1024
             --max-depth 3 --threads 1 --estimator "$default_estimator" -o out.png --hdr out.pfm)

# Starts RANKS ranks of the long render in the background (stderr to err.log, so progress comes
# as a line per tenth) and returns once a line shows at least 10% done. Sets $pid to mpirun's.
start_long_render() { # RANKS [MPIRUN OPTIONS...] -- [PROGRAM OPTIONS...]
  local ranks=$1 mpi_options=() options=()
  shift
  while (($#)) && [[ $1 != -- ]]; do mpi_options+=("$1"); shift; done
  (($#)) && shift
  options=("$@")
  # mpirun itself in the background (not a function, whose subshell would get the signals).
  "$mpiexec" --oversubscribe --bind-to none -n "$ranks" "${mpi_options[@]}" "$mpi_program" \
    "${long_render[@]}" "${options[@]}" 2>err.log &
  pid=$!
  until grep -q '^\[ *[1-9][0-9]%\]' err.log; do
    kill -0 "$pid" 2>/dev/null || { wait "$pid"; fail "the render ended (status $?) before 10%"; }
    sleep 0.05
  done
}

# The pid of rank RANK among mpirun's children.
rank_pid() { # RANK
  local child
  for child in $(pgrep -P "$pid"); do
    if tr '\0' '\n' <"/proc/$child/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$1"; then
      echo "$child"
      return 0
    fi
  done
  return 1
}

# A rank killed mid-render: mpirun ends the run with a non-zero status, and no image is written.
case_killed_rank() {
  start_long_render 3 --
  local victim
  victim=$(rank_pid 1) || fail "rank 1 not found among mpirun's children"
  kill -s KILL "$victim"
  wait "$pid"
  local status=$?
  ((status != 0)) || fail "exit status 0 after a rank was killed"
  [[ ! -e out.png && ! -e out.pfm ]] || fail "an image was written"
  no_temporaries
}

# SIGNAL to mpirun stops after the current pass: rank 0 writes the image of the passes done
# and the checkpoint, which glint-render resumes to its own uninterrupted bytes. mpirun passes
# SIGUSR1 on as it is, and exits with rank 0's status; it answers SIGTERM with SIGTERM to every
# rank and SIGKILL a second later (this render's passes take a small part of it), and exits
# with a status of its own: STATUS "any" accepts any but 0.
case_stopped() { # SIGNAL STATUS
  glint_render "${long_render[@]}" -o full.png --hdr full.pfm --threads 2 --quiet ||
    fail "the full render failed"
  start_long_render 2 -- --checkpoint ck.glint
  kill -s "$1" "$pid"
  wait "$pid"
  local status=$?
  if [[ $2 == any ]]; then
    ((status != 0)) || fail "exit status 0"
  else
    ((status == $2)) || fail "exit status $status, expected $2"
  fi
  local pattern="^glint-render-mpi: stopped by SIG$1: out\.png holds ([0-9]+) of 1024 samples per pixel \(([0-9]+) of 37 passes\)$"
  grep -Eq "$pattern" err.log || fail "no stop message"
  [[ -f out.png && -f out.pfm && -f ck.glint ]] || fail "the image or the checkpoint is missing"
  no_temporaries
  glint_render "${long_render[@]}" --threads 2 --resume ck.glint 2>err.log ||
    fail "glint-render --resume failed (status $?)"
  cmp out.png full.png && cmp out.pfm full.pfm || fail "the resumed image differs"
}

run_case "$case_name" "$@"
echo "ok: $case_name $*"
