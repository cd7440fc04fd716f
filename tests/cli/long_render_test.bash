#!/usr/bin/env bash
# glint-render's promises for long renders, the ones that need a shell (signals, job control,
# ulimit, symbolic links):
#
#   long_render_test.bash CASE PROGRAM SCENE SCRATCH [OTHER_PROGRAM]
#
# CASE is one of the functions below named case_*; it runs PROGRAM on SCENE in the empty
# directory SCRATCH. OTHER_PROGRAM is a glint-render of another variant (glint-render-report). No case depends on how fast the machine is: a signal is sent only once
# the progress on stderr shows that passes have completed, and the render is long enough
# that it is still running then by a wide margin. Exit status 0 on success, 77 when the case
# cannot run here (ctest's SKIP_RETURN_CODE), 1 on a failure, with the reason on stderr.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
case_name=$1 program=$2 scene=$3 scratch=$4 other_program=${5:-}

enter_scratch "$scratch"

# No temporary of any name is left behind.
no_temporaries() {
  local left
  left=$(find . -name '*glint-partial*' ! -type l -print)
  [[ -z $left ]] || fail "temporaries left behind: $left"
}

# Whether the program writes --exr: one built without OpenEXR refuses it, saying so. Its output is
# read whole, not piped to grep: under pipefail the refusal's own status 2 would fail the pipe.
built_with_exr() {
  local refusal
  refusal=$("$program" --exr x.exr 2>&1)
  [[ $refusal != *"without OpenEXR"* ]]
}

# A PNG whose last chunk is IEND, and a PFM of exactly the size its header promises: complete
# files, not truncated ones.
complete_png() {
  [[ -f $1 && ! -L $1 ]] || fail "$1 is not a regular file"
  [[ $(tail -c 12 "$1" | od -An -tx1 | tr -d ' \n') == 0000000049454e44ae426082 ]] ||
    fail "$1 does not end with an IEND chunk"
}
complete_pfm() { # FILE WIDTH HEIGHT
  [[ -f $1 && ! -L $1 ]] || fail "$1 is not a regular file"
  local header="PF
$2 $3
-1.0
"
  local size
  size=$(stat -c %s "$1")
  ((size == ${#header} + $2 * $3 * 12)) || fail "$1 has $size bytes, not a complete $2x$3 PFM"
}

# A render of 320x240 pixels at 1024 samples per pixel: passes of 1, 1, 2, 4, ... 32, then 32
# samples at a time, so the first 10% of the work holds several completed passes and the
# render still has about 90% of its work ahead when it is interrupted there (some seconds on 2
# threads of a Zen 5: a quarter of the pixels could end before the signal arrives).
# GLINT_LONG_RENDER_SIZE=WxH changes the size: the sanitizers' build (CMake's GLINT_SANITIZE),
# where glint-render is some 15 times slower, takes a quarter of the pixels.
long_size=${GLINT_LONG_RENDER_SIZE:-320x240}
[[ $long_size =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] ||
  fail "GLINT_LONG_RENDER_SIZE is '$long_size', not WIDTHxHEIGHT"
long_width=${BASH_REMATCH[1]} long_height=${BASH_REMATCH[2]}
long_render=(--width "$long_width" --height "$long_height" --spp 1024 --max-depth 3 --threads 2
             -o out.png --hdr out.pfm)

# Starts a long render in the background (stderr is a file, so progress comes as a line per
# tenth) and returns once a progress line shows at least 10% done; $pid is the process started,
# glint-render itself or, with the command `launcher` set, that command running it.
launcher=()
start_long_render() {
  # Job control: a background job of a script would otherwise ignore SIGINT, and glint-render
  # keeps an ignored SIGINT ignored (as nohup and `&` expect).
  # Emptied here, before the render starts: the loop below must not read an earlier run's log.
  : >err.log
  set -m
  "${launcher[@]}" "$program" "$scene" "${long_render[@]}" "$@" 2>err.log &
  pid=$!
  set +m
  until grep -q '^\[ *[1-9][0-9]%\]' err.log; do
    kill -0 "$pid" 2>/dev/null || { wait "$pid"; fail "glint-render ended (status $?) before 10%"; }
    sleep 0.05
  done
}

# The first signal: the current pass completes, the image of the passes done is written,
# and the exit status says which signal it was.
interrupted_once() { # SIGNAL STATUS
  start_long_render
  kill -s "$1" "$pid"
  wait "$pid"
  local status=$?
  ((status == $2)) || fail "exit status $status, expected $2"
  local pattern="^glint-render: stopped by SIG$1: out\.png holds ([0-9]+) of 1024 samples per pixel \(([0-9]+) of 37 passes\)$"
  local message
  message=$(tail -n 1 err.log)
  [[ $message =~ $pattern ]] || fail "last line on stderr is not the stop message: '$message'"
  local spp=${BASH_REMATCH[1]} passes=${BASH_REMATCH[2]}
  # At least the passes up to 10% (102 samples: 96 is the end of pass 8) are done, and the
  # count is the end of a pass: 1, 2, 4, ... 32, then multiples of 32.
  ((spp >= 96 && spp < 1024 && spp % 32 == 0 && passes == spp / 32 + 5)) ||
    fail "$spp samples per pixel in $passes passes is not a pass boundary past 10%"
  grep -q "^glint-render (.*): .* -> out\.png: ${long_width}x${long_height}, $spp spp," err.log ||
    fail "the summary line does not give $spp spp"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

case_sigint() { interrupted_once INT 130; }
case_sigterm() { interrupted_once TERM 143; }
case_sighup() { interrupted_once HUP 129; }
# Batch systems' and CPU limits' ways of saying that time is up: stops too, not deaths.
case_sigusr1() { interrupted_once USR1 138; }
case_sigalrm() { interrupted_once ALRM 142; }
case_sigxcpu() { interrupted_once XCPU 152; }

# Past a soft CPU-time limit (ulimit -St) the kernel sends SIGXCPU again every second of CPU
# time: the copies after the first are the same stop, not a second signal.
case_repeated_sigxcpu() {
  start_long_render
  kill -s XCPU "$pid"
  sleep 1.2
  kill -s XCPU "$pid" 2>/dev/null
  wait "$pid"
  local status=$?
  ((status == 152)) || fail "exit status $status, expected 152"
  ! grep -q "a second stop signal" err.log || fail "a repeated SIGXCPU was a second stop"
  grep -q "^glint-render: stopped by SIGXCPU: out\.png holds" err.log || fail "no stop message"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

# Progress is a side channel: a reader of stderr that goes away (`glint-render ... 2>&1 | head`)
# ends the progress, not the render. The reader takes the first line and exits while the render
# has seconds to go; the images are written whole and the status is 0.
case_progress_reader_closes() {
  { "$program" "$scene" "${long_render[@]}" --spp 256 2>&1 >/dev/null; echo $? >status; } |
    head -n 1 >first.log
  local status
  status=$(cat status)
  ((status == 0)) || fail "exit status $status, expected 0 (141: killed by SIGPIPE)"
  grep -q '^\[ *[0-9]*%\]' first.log || fail "the reader got no progress line: $(cat first.log)"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

# Memory that cannot be had (`ulimit -v`, 1 GB; the image's sums alone are 1.6 GB): the message
# says what needed it and how much, and nothing is written. Status 77 where the limit cannot be
# set or the program cannot run under it at all (a sanitizer's shadow memory).
case_out_of_memory() {
  (ulimit -v 1000000 && "$program" --help >/dev/null 2>&1) || exit 77
  local err status
  err=$(ulimit -v 1000000 && "$program" "$scene" -o out.png --width 32768 --height 2048 --spp 1 2>&1)
  status=$?
  ((status == 1)) || fail "exit status $status, expected 1: $err"
  [[ $err == *"glint-render: error: out of memory for the image of 32768x2048 pixels: rendering it needs about 2.42 GB (36 bytes a pixel: its sums, its film)"* ]] ||
    fail "unexpected message: $err"
  [[ $err != *bad_alloc* ]] || fail "the message names std::bad_alloc: $err"
  [[ ! -e out.png ]] || fail "out.png was written"
  no_temporaries
}

# A supervisor's stop: SIGTERM to the process and at once to its process group (the job
# control of start_long_render makes the render its group's leader), as `timeout`, systemd and
# job schedulers send it. The two copies are one stop: the image is written, every time.
case_group_signal() {
  local run
  for run in 1 2 3; do
    start_long_render
    kill -s TERM "$pid"
    kill -s TERM -- "-$pid"
    wait "$pid"
    local status=$?
    ((status == 143)) || fail "run $run: exit status $status, expected 143"
    grep -q "^glint-render: stopped by SIGTERM: out\.png holds" err.log ||
      fail "run $run: no stop message"
    complete_png out.png
    complete_pfm out.pfm "$long_width" "$long_height"
    no_temporaries
    rm -f out.png out.pfm
  done
}

# GNU timeout stopping the render: told to stop (here by a SIGTERM of its own, once the render
# is under way, rather than after a time that depends on the machine), it sends SIGTERM to the
# render and then to the render's process group, and exits with the render's status.
case_timeout() {
  command -v timeout >/dev/null || exit 77
  launcher=(timeout 600)
  start_long_render
  kill -s TERM "$pid"
  wait "$pid"
  local status=$?
  ((status == 143)) || fail "exit status $status, expected 143"
  grep -q "^glint-render: stopped by SIGTERM: out\.png holds" err.log || fail "no stop message"
  ! grep -q "a second stop signal" err.log || fail "timeout's two copies of SIGTERM were two stops"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

# A second signal ends the run at once: nothing written, no temporary left. Two different
# signals: a second SIGINT sent before the first is delivered would merge with it, and one
# within a second of the first is taken as another copy of the same stop.
case_second_signal() {
  start_long_render
  kill -s INT "$pid"
  kill -s TERM "$pid"
  wait "$pid"
  local status=$?
  ((status == 143 || status == 130)) || fail "exit status $status, expected 143 (or 130)"
  grep -q "a second stop signal: exiting at once" err.log || fail "no message for the second signal"
  [[ ! -e out.png && ! -e out.pfm ]] || fail "an image was written"
  no_temporaries
}

# --quiet keeps the stop message: it says what the file holds.
case_sigint_quiet() {
  set -m
  "$program" "$scene" "${long_render[@]}" --quiet 2>err.log &
  pid=$!
  set +m
  # Nothing is printed before the stop, so wait until the process has used 0.3 s of CPU:
  # it is rendering then (this scene loads in microseconds), so its handlers are in place and
  # the first pass, which always completes, has begun.
  local ticks=$(($(getconf CLK_TCK) * 3 / 10))
  until (($(awk '{ print $14 + $15 }' "/proc/$pid/stat" 2>/dev/null || echo 0) >= ticks)); do
    kill -0 "$pid" 2>/dev/null || { wait "$pid"; fail "glint-render ended (status $?) early"; }
    sleep 0.05
  done
  kill -s INT "$pid"
  wait "$pid"
  local status=$?
  ((status == 130)) || fail "exit status $status, expected 130"
  grep -Eq "^glint-render: stopped by SIGINT: out\.png holds [0-9]+ of 1024 samples per pixel" err.log ||
    fail "no stop message"
  [[ $(wc -l <err.log) -eq 1 ]] || fail "--quiet printed more than the stop message"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

# Symbolic links planted at the names an older glint-render used as temporaries, and at the
# targets themselves: none is written through; the targets become regular files.
case_planted_symlinks() {
  echo precious >victim
  echo also-precious >victim2
  ln -s victim out.png.glint-partial
  ln -s victim out.pfm.glint-partial
  ln -s victim2 out.png
  "$program" "$scene" -o out.png --hdr out.pfm --spp 2 2>err.log || fail "exit status $?"
  [[ $(cat victim) == precious && $(cat victim2) == also-precious ]] ||
    fail "a file behind a planted link was overwritten"
  [[ $(readlink out.png.glint-partial) == victim && $(readlink out.pfm.glint-partial) == victim ]] ||
    fail "a planted link was changed"
  complete_png out.png
  complete_pfm out.pfm 24 16
  no_temporaries
}

# The PFM fails while being written (past `ulimit -f`, after the PNG's temporary was
# written): neither image is renamed into place, and an older out.png stays as it was.
case_hdr_fails_while_writing() {
  echo old >out.png
  local err status
  # 2 KiB: the PNG (about 600 bytes) fits, the PFM (4.6 KB) does not. stderr goes to a pipe,
  # which the limit does not cover.
  err=$(ulimit -f 2 && "$program" "$scene" -o out.png --hdr out.pfm --spp 2 --quiet 2>&1)
  status=$?
  ((status == 1)) || fail "exit status $status, expected 1: $err"
  [[ $err == *"cannot write out.pfm: File too large"* ]] || fail "unexpected message: $err"
  [[ $(cat out.png) == old ]] || fail "out.png was replaced although out.pfm failed"
  [[ ! -e out.pfm ]] || fail "out.pfm exists"
  no_temporaries
}

# A checkpoint that cannot be written at the end (the disk full: here a file size limit that
# the images fit under, the checkpoint of 24 bytes a pixel not; or its directory removed
# during the render): the images are written whole all the same, and the status is 1 with the
# checkpoint named last. For a complete render, one stopped by --time-limit and one by SIGINT.
checkpoint_limit=$((long_width * long_height * 18 / 1024)) # blocks: above the PFM, below it
with_exr=()
built_with_exr && with_exr=(--exr out.exr)
images_whole_without_checkpoint() { # STATUS_FOUND CHECKPOINT PROBLEM
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  if ((${#with_exr[@]})); then
    [[ $(head -c 4 out.exr | od -An -tx1 | tr -d ' \n') == 762f3101 ]] || fail "out.exr is no EXR"
  fi
  (($1 == 1)) || fail "exit status $1, expected 1"
  local message
  message=$(tail -n 1 err.log)
  [[ $message == "glint-render: error: no checkpoint: cannot write $2: $3 (the images were written)" ]] ||
    fail "last line on stderr is not the checkpoint's failure: '$message'"
  ! grep -q "holds the render so far" err.log || fail "the missing checkpoint is offered for --resume"
  [[ ! -e $2 ]] || fail "$2 exists"
  no_temporaries
}
case_checkpoint_fails_complete() {
  (ulimit -f "$checkpoint_limit" &&
    "$program" "$scene" "${long_render[@]}" "${with_exr[@]}" --spp 4 --checkpoint ck.glint 2>err.log)
  images_whole_without_checkpoint $? ck.glint "File too large"
  grep -q "^glint-render (.*): .* -> out\.png: ${long_width}x${long_height}, 4 spp," err.log ||
    fail "no summary line"
}
case_checkpoint_fails_time_limit() {
  (ulimit -f "$checkpoint_limit" &&
    "$program" "$scene" "${long_render[@]}" "${with_exr[@]}" --time-limit 0 --checkpoint ck.glint 2>err.log)
  images_whole_without_checkpoint $? ck.glint "File too large"
  grep -q "^glint-render: time limit of 0 s reached: out\.png holds 1 of 1024 samples" err.log ||
    fail "no time limit message"
}
case_checkpoint_fails_sigint() {
  launcher=(bash -c 'ulimit -f "$0" && exec "$@"' "$checkpoint_limit")
  start_long_render "${with_exr[@]}" --checkpoint ck.glint
  kill -s INT "$pid"
  wait "$pid"
  images_whole_without_checkpoint $? ck.glint "File too large"
  grep -q "^glint-render: stopped by SIGINT: out\.png holds" err.log || fail "no stop message"
}
case_checkpoint_directory_vanishes() {
  mkdir gone
  start_long_render "${with_exr[@]}" --checkpoint gone/ck.glint
  rm -r gone
  kill -s INT "$pid"
  wait "$pid"
  images_whole_without_checkpoint $? gone/ck.glint "No such file or directory"
}

# Outputs that cannot be written are refused before the render: no progress line appears.
refused_before_render() { # STDERR_PATTERN ARGS...
  local pattern=$1
  shift
  "$program" "$@" 2>err.log
  local status=$?
  ((status == 1)) || fail "exit status $status, expected 1"
  grep -Eq "$pattern" err.log || fail "stderr does not match '$pattern'"
  ! grep -q elapsed err.log || fail "the render started before the output was refused"
  no_temporaries
}

# A second output whose name the file system refuses (256 bytes, one more than NAME_MAX) is
# refused before the render, and the first output's old file stays as it was, byte for byte;
# so for --exr and --checkpoint.
case_long_second_name() {
  "$program" "$scene" -o short.png --spp 2 --quiet 2>err.log || fail "the first render failed"
  cp short.png before.png
  local long
  long=$(printf '%0252d' 0)
  refused_before_render \
    "^glint-render: error: cannot write 0+\.pfm: the file name is 256 bytes long, more than the 255 its file system allows$" \
    "$scene" -o short.png --hdr "$long.pfm"
  refused_before_render "^glint-render: error: cannot write 0+\.glint: the file name is 258 bytes long" \
    "$scene" -o short.png --hdr out.pfm --checkpoint "$long.glint"
  if built_with_exr; then
    refused_before_render "^glint-render: error: cannot write 0+\.exr: the file name is 256 bytes long" \
      "$scene" -o short.png --exr "$long.exr"
  fi
  cmp -s short.png before.png || fail "short.png was replaced"
  [[ ! -e out.pfm ]] || fail "out.pfm was written"
}

case_hdr_is_directory() {
  mkdir out.pfm
  refused_before_render "^glint-render: error: cannot write out\.pfm: it is a directory$" \
    "$scene" -o out.png --hdr out.pfm
  [[ ! -e out.png && -d out.pfm ]] || fail "out.png was written or out.pfm changed"
}

case_output_is_directory() {
  mkdir out.png
  refused_before_render "^glint-render: error: cannot write out\.png: it is a directory$" \
    "$scene" -o out.png
  [[ -d out.png ]] || fail "out.png changed"
}

case_read_only_directory() {
  # Permissions do not bind root, which could write there after all.
  ((EUID != 0)) || { echo "skipped: running as root"; exit 77; }
  mkdir ro && chmod 555 ro
  refused_before_render "cannot write ro/out\.png: directory ro is not writable" \
    "$scene" -o ro/out.png
  chmod 755 ro
  [[ -z $(ls ro) ]] || fail "something was written in ro"
}

# A scene file whose name ends in .png is its own default output: refused, left intact,
# however its name is spelt.
case_scene_is_output() {
  cp "$scene" x.png
  refused_before_render "^glint-render: error: cannot write x\.png: it is the scene file x\.png$" \
    x.png
  refused_before_render "^glint-render: error: cannot write x\.png: it is the scene file \./x\.png$" \
    ./x.png --hdr x.pfm
  cmp -s "$scene" x.png || fail "the scene file was changed"
}

# Thread stacks that cannot be mapped (each as large as `ulimit -s`, within `ulimit -v`): a
# clear error before any rendering, not one after it.
case_threads_fail() {
  local err status
  err=$(ulimit -s 1000000 && ulimit -v 2500000 &&
    "$program" "$scene" -o out.png --threads 64 --width 256 --height 256 2>&1)
  status=$?
  ((status == 1)) || fail "exit status $status, expected 1: $err"
  [[ $err =~ "glint-render: error: cannot start 64 rendering threads (started "[0-9]+"): " ]] ||
    fail "unexpected message: $err"
  [[ $err != *elapsed* ]] || fail "the render started: $err"
  [[ ! -e out.png ]] || fail "out.png was written"
}

# The long render, uninterrupted, as full.png and full.pfm: what every resumed render must
# give byte for byte.
render_full() {
  "$program" "$scene" "${long_render[@]}" -o full.png --hdr full.pfm --quiet 2>err.log ||
    fail "the uninterrupted render failed (status $?)"
}

# SIGINT with --checkpoint, then --resume (with another thread count): the bytes of an
# uninterrupted render. Resuming the finished checkpoint again renders nothing new.
case_checkpoint_resume() {
  render_full
  start_long_render --checkpoint ck.glint
  kill -s INT "$pid"
  wait "$pid"
  local status=$?
  ((status == 130)) || fail "exit status $status, expected 130"
  # PROGRAM may be a variant's glint-render-VARIANT, which says its own name.
  grep -Eq "^glint-render(-[a-z-]+)?: ck\.glint holds the render so far: continue it with --resume ck\.glint$" \
    err.log || fail "no message about the checkpoint"
  [[ $(tail -n 1 err.log) =~ ^glint-render(-[a-z-]+)?": stopped by SIGINT: out.png holds " ]] ||
    fail "the stop message is not the last line"
  [[ -f ck.glint ]] || fail "no checkpoint written"
  complete_png out.png
  ! cmp -s out.png full.png || fail "the interrupted image is already the full one"
  no_temporaries

  "$program" "$scene" "${long_render[@]}" --threads 1 --resume ck.glint --checkpoint ck.glint \
    2>err.log || fail "the resumed render failed (status $?)"
  cmp out.png full.png || fail "the resumed PNG differs from the uninterrupted one"
  cmp out.pfm full.pfm || fail "the resumed PFM differs from the uninterrupted one"
  ! grep -q "holds the render so far" err.log || fail "a finished render calls itself unfinished"
  rm out.png out.pfm
  "$program" "$scene" "${long_render[@]}" --resume ck.glint 2>err.log ||
    fail "resuming a finished checkpoint failed (status $?)"
  cmp out.png full.png && cmp out.pfm full.pfm || fail "the finished checkpoint's image differs"
  no_temporaries
}

# Killed outright (no chance to write at exit) after a checkpoint was written between passes:
# resuming that one still gives the uninterrupted render's bytes.
case_checkpoint_after_kill() {
  render_full
  start_long_render --checkpoint ck.glint --checkpoint-interval 0
  until [[ -f ck.glint ]]; do
    kill -0 "$pid" 2>/dev/null || { wait "$pid"; fail "glint-render ended (status $?) early"; }
    sleep 0.05
  done
  kill -s KILL "$pid"
  wait "$pid" 2>/dev/null  # without the shell's "Killed" line
  [[ ! -e out.png ]] || fail "an image was written"
  "$program" "$scene" "${long_render[@]}" --resume ck.glint 2>err.log ||
    fail "the resumed render failed (status $?)"
  cmp out.png full.png && cmp out.pfm full.pfm || fail "the resumed image differs"
}

# A checkpoint of another scene (or of the scene with another image on a sphere), sample count
# or variant, or a damaged one: refused before rendering, naming the file and the difference.
case_resume_refused() {
  "$program" "$scene" "${long_render[@]}" --time-limit 0 --checkpoint ck.glint --quiet 2>err.log ||
    fail "making the checkpoint failed (status $?)"
  rm out.png out.pfm
  cp "$scene" other.scene && echo "# one more line" >>other.scene
  refused_before_render "^glint-render: error: cannot resume from ck\.glint: it was made from another scene" \
    other.scene "${long_render[@]}" --resume ck.glint
  refused_before_render "^glint-render: error: cannot resume from ck\.glint: it was made with samples per pixel 1024, this render has 512$" \
    "$scene" "${long_render[@]}" --spp 512 --resume ck.glint
  refused_before_render "^glint-render: error: cannot resume from ck\.glint: it was made with seed 0, this render has 7$" \
    "$scene" "${long_render[@]}" --seed 7 --resume ck.glint
  if [[ -n $other_program ]]; then
    program=$other_program refused_before_render \
      "^glint-render-report: error: cannot resume from ck\.glint: it was made by variant '[a-z_]+', this is variant 'report' \(glint-render-[a-z-]+ continues it\)$" \
      "$scene" "${long_render[@]}" --resume ck.glint
  fi
  head -c 100 ck.glint >short.glint
  refused_before_render "^glint-render: error: cannot resume from short\.glint: it is truncated" \
    "$scene" "${long_render[@]}" --resume short.glint
  refused_before_render "^glint-render: error: cannot resume from .*/$(basename "$scene" .scene)\.scene: it is not a glint checkpoint" \
    "$scene" "${long_render[@]}" --resume "$scene"
  [[ ! -e out.png && ! -e out.pfm ]] || fail "an image was written"
  # The images a scene's spheres show are part of it: one changed since the checkpoint makes it
  # another scene's, though the scene file is the same.
  "$program" "$scene" --width 8 --height 4 --spp 1 -o map.png --quiet || fail "the map: $?"
  { cat "$scene"; echo; echo "sphere center=0,0,-1000 radius=1 texture=map.png"; } >textured.scene
  "$program" textured.scene "${long_render[@]}" --time-limit 0 --checkpoint tex.glint --quiet \
    2>err.log || fail "making the textured checkpoint failed (status $?)"
  rm out.png out.pfm
  "$program" "$scene" --width 4 --height 2 --spp 1 -o map.png --quiet || fail "the map: $?"
  refused_before_render "^glint-render: error: cannot resume from tex\.glint: it was made from another scene \(the scene file's bytes or its images differ\)$" \
    textured.scene "${long_render[@]}" --resume tex.glint
  [[ ! -e out.png && ! -e out.pfm ]] || fail "an image was written"
}

# A run repeated with an existing --checkpoint and no --resume would replace a longer render
# with a shorter one: refused before rendering, the checkpoint as it was. Resumed from it, the
# same file is replaced.
case_checkpoint_exists() {
  "$program" "$scene" "${long_render[@]}" --time-limit 0 --checkpoint ck.glint --quiet 2>err.log ||
    fail "making the checkpoint failed (status $?)"
  cp ck.glint before.glint
  rm out.png out.pfm
  refused_before_render \
    "^glint-render: error: cannot write the checkpoint ck\.glint: it exists, and may hold more of the render than this run will: continue it with --resume ck\.glint, or remove it to start again$" \
    "$scene" "${long_render[@]}" --checkpoint ck.glint
  cmp -s ck.glint before.glint || fail "the checkpoint was changed"
  [[ ! -e out.png && ! -e out.pfm ]] || fail "an image was written"
  "$program" "$scene" "${long_render[@]}" --time-limit 0 --resume ck.glint --checkpoint ck.glint \
    --quiet 2>err.log || fail "resuming into the same file failed (status $?)"
  ! cmp -s ck.glint before.glint || fail "the resumed render's checkpoint was not written"
}

# Temporaries a killed run left beside the targets (kill -9 while a checkpoint was written) are
# removed at the start; files of other names, of other targets, and symbolic links stay.
case_stale_temporaries() {
  echo stale >ck.glint.0123456789ab.glint-partial
  echo stale >out.png.abcdef012345.glint-partial
  echo precious >victim
  ln -s victim ck.glint.fedcba987654.glint-partial
  echo keep >ck.glint.0123456789AB.glint-partial
  echo keep >other.glint.0123456789ab.glint-partial
  echo keep >ck.glint.012345.glint-partial
  "$program" "$scene" -o out.png --spp 2 --checkpoint ck.glint --quiet 2>err.log ||
    fail "exit status $?"
  [[ ! -e ck.glint.0123456789ab.glint-partial && ! -e out.png.abcdef012345.glint-partial ]] ||
    fail "a stale temporary was left"
  [[ -L ck.glint.fedcba987654.glint-partial && $(cat victim) == precious ]] ||
    fail "a symbolic link, or what it points to, was changed"
  [[ -f ck.glint.0123456789AB.glint-partial && -f other.glint.0123456789ab.glint-partial &&
    -f ck.glint.012345.glint-partial ]] || fail "a file that is no temporary of a target was removed"
  complete_png out.png
}

# --time-limit 0: the first pass, then a complete image of 1 sample per pixel, status 0.
case_time_limit_zero() {
  "$program" "$scene" "${long_render[@]}" --time-limit 0 2>err.log
  local status=$?
  ((status == 0)) || fail "exit status $status, expected 0"
  [[ $(tail -n 1 err.log) == "glint-render: time limit of 0 s reached: out.png holds 1 of 1024 samples per pixel (1 of 37 passes)" ]] ||
    fail "last line on stderr is not the time limit message"
  grep -q "^glint-render (.*): .* -> out\.png: ${long_width}x${long_height}, 1 spp," err.log ||
    fail "the summary line does not give 1 spp"
  complete_png out.png
  complete_pfm out.pfm "$long_width" "$long_height"
  no_temporaries
}

# Samples near the float range: a float sum of them overflowed to infinite pixels, with exit 0
# and no word. Their sums are double now: the images are finite (and no sample is invalid).
finite_pfm() { # FILE
  local values
  values=$(tail -c +$(($(head -n 3 "$1" | wc -c) + 1)) "$1" | od -An -v -tf4)
  [[ -n $values ]] || fail "$1 holds no pixels"
  ! grep -Eqi 'inf|nan' <<<"$values" || fail "$1 holds pixels that are not finite"
}
case_huge_values() {
  printf '%s\n' 'image width=6 height=4 spp=1000 max_depth=3' 'background color=1e36,1e36,1e36' \
    'sphere center=0,0,0 radius=1' >background.scene
  printf '%s\n' 'image width=6 height=4 spp=4 max_depth=3' 'camera position=0,0,10 look_at=0,0,0' \
    'sphere center=0,0,0 radius=5 emission=1e38,1e38,1e38' >lamp.scene
  for name in background lamp; do
    "$program" $name.scene -o $name.png --hdr $name.pfm 2>err.log || fail "$name: exit status $?"
    ! grep -q "warning" err.log || fail "$name: a warning"
    complete_pfm $name.pfm 6 4
    finite_pfm $name.pfm
  done
  no_temporaries
}

run_case "$case_name"
echo "ok: $case_name"
