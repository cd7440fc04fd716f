# End-to-end checks of the glint-render command line: exit codes, messages, outputs.

# glint-render's progress printer (apps/progress_printer.hpp) on fixed sequences of
# reports, glint-render-mpi's scheduling (apps/tile_scheduler.hpp), which needs no MPI, and
# the programs' CPU check's message (apps/cpu_check.hpp).
add_executable(glint-cli-tests ${CMAKE_CURRENT_LIST_DIR}/progress_printer_test.cpp
                               ${CMAKE_CURRENT_LIST_DIR}/tile_scheduler_test.cpp
                               ${CMAKE_CURRENT_LIST_DIR}/cpu_check_test.cpp)
target_include_directories(glint-cli-tests PRIVATE ${PROJECT_SOURCE_DIR}/apps)
target_link_libraries(glint-cli-tests PRIVATE glint::glint glint_project_options glint_catch_main)
catch_discover_tests(glint-cli-tests TEST_PREFIX "cli: "
                     PROPERTIES LABELS cli TIMEOUT ${GLINT_TEST_TIMEOUT})

if(NOT TARGET glint-render)
  return()
endif()
set(glint_cli_scenes ${CMAKE_CURRENT_LIST_DIR}/scenes)

# A checkpoint rewritten with another variant name, its hashes whole (tests/cli/checkpoint_forge.cpp):
# an older checkpoint's name, or a hostile one.
add_executable(glint-checkpoint-forge ${CMAKE_CURRENT_LIST_DIR}/checkpoint_forge.cpp)
target_link_libraries(glint-checkpoint-forge PRIVATE glint::glint glint_project_options)

function(glint_cli_test name)
  cmake_parse_arguments(arg "EXPECT_OUTPUT" "STATUS;STDERR;STDOUT;OUTPUT;PROGRAM" "ARGS" ${ARGN})
  if(NOT arg_PROGRAM)
    set(arg_PROGRAM glint-render)
  endif()
  # Arguments travel as one '|'-joined string: a ';' list would be split by add_test.
  string(REPLACE ";" "|" joined_args "${arg_ARGS}")
  set(defines -DPROGRAM=$<TARGET_FILE:${arg_PROGRAM}> "-DARGS=${joined_args}"
      -DEXPECT_STATUS=${arg_STATUS} -DSCRATCH=${PROJECT_BINARY_DIR}/cli-test/${name})
  if(DEFINED arg_STDERR)
    list(APPEND defines "-DEXPECT_STDERR=${arg_STDERR}")
  endif()
  if(DEFINED arg_STDOUT)
    list(APPEND defines "-DEXPECT_STDOUT=${arg_STDOUT}")
  endif()
  if(DEFINED arg_OUTPUT)
    list(APPEND defines -DOUTPUT=${arg_OUTPUT} -DEXPECT_OUTPUT=${arg_EXPECT_OUTPUT})
  endif()
  add_test(NAME "cli: ${name}" COMMAND ${CMAKE_COMMAND} ${defines}
           -P ${CMAKE_CURRENT_LIST_DIR}/run_cli.cmake)
  set_tests_properties("cli: ${name}" PROPERTIES LABELS cli)
endfunction()

glint_cli_test(help STATUS 0 STDOUT "usage: glint-render SCENE" ARGS --help)
glint_cli_test(no-arguments STATUS 2 STDERR "no scene file given")
glint_cli_test(unknown-option STATUS 2
               STDERR "unknown option '--frobnicate'.Run 'glint-render[-a-z]* --help' for the options"
               ARGS ${glint_cli_scenes}/tiny.scene --frobnicate)
# A near miss of an option's name (found in the usage text) is named.
glint_cli_test(misspelt-option STATUS 2
               STDERR "unknown option '--max_depth' .did you mean '--max-depth'.."
               ARGS ${glint_cli_scenes}/tiny.scene --max_depth 3)
glint_cli_test(bad-spp STATUS 2 STDERR "--spp expects an integer"
               ARGS ${glint_cli_scenes}/tiny.scene --spp 12x)
glint_cli_test(zero-width STATUS 2 STDERR "--width expects an integer"
               ARGS ${glint_cli_scenes}/tiny.scene --width 0)
glint_cli_test(missing-value STATUS 2 STDERR "--seed needs a value"
               ARGS ${glint_cli_scenes}/tiny.scene --seed)
glint_cli_test(missing-scene STATUS 1 STDERR "no-such.scene.*cannot open"
               ARGS no-such.scene -o out.png OUTPUT out.png)
glint_cli_test(overlapping-glass STATUS 1
               STDERR "overlapping-glass.scene:[0-9]+: error: transparent spheres at lines [0-9]+ and [0-9]+"
               ARGS ${glint_cli_scenes}/overlapping-glass.scene -o out.png OUTPUT out.png)
# Geometry beyond the limits of float arithmetic is refused with the limit named, not rendered
# black (a floor of radius 2e10).
glint_cli_test(huge-radius STATUS 1
               STDERR "huge-radius.scene:5: error: sphere radius must be at most 1e.10 .the scene format's limit., got 2e.10"
               ARGS ${PROJECT_SOURCE_DIR}/scenes/invalid/huge-radius.scene -o out.png OUTPUT out.png)
# Endless devices as the scene or the checkpoint to resume: refused from their first bytes.
glint_cli_test(scene-dev-zero STATUS 1 STDERR "^/dev/zero:1: error: line contains a NUL byte"
               ARGS /dev/zero -o out.png OUTPUT out.png)
glint_cli_test(resume-dev-zero STATUS 1
               STDERR "cannot resume from /dev/zero: it is not a glint checkpoint"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --resume /dev/zero OUTPUT out.png)
glint_cli_test(resume-dev-urandom STATUS 1 STDERR "cannot resume from /dev/urandom: "
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --resume /dev/urandom OUTPUT out.png)
glint_cli_test(missing-output-directory STATUS 1 STDERR "directory .* does not exist"
               ARGS ${glint_cli_scenes}/tiny.scene -o nowhere/out.png)
glint_cli_test(output-not-png STATUS 2 STDERR "-o writes an 8-bit sRGB PNG: the file name must end in .png, got 'out.jpg'"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.jpg OUTPUT out.jpg)
glint_cli_test(hdr-not-pfm STATUS 2 STDERR "--hdr writes a linear float PFM: the file name must end in .pfm"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.exr OUTPUT out.png)
glint_cli_test(renders STATUS 0 STDERR "Mrays/s" EXPECT_OUTPUT OUTPUT out.png
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.pfm --spp 2)
# Tone mapping of the PNG: the operator names and the exposure range come from tone_map.hpp.
glint_cli_test(bad-tonemap STATUS 2 STDERR "--tonemap expects clip, reinhard or aces, got 'filmic'"
               ARGS ${glint_cli_scenes}/tiny.scene --tonemap filmic)
glint_cli_test(bad-exposure STATUS 2 STDERR "--exposure expects stops from -64 to 64, got '65'"
               ARGS ${glint_cli_scenes}/tiny.scene --exposure 65)
glint_cli_test(nan-exposure STATUS 2 STDERR "--exposure expects stops from -64 to 64, got 'nan'"
               ARGS ${glint_cli_scenes}/tiny.scene --exposure nan)
glint_cli_test(tonemap-aces STATUS 0 EXPECT_OUTPUT OUTPUT out.png
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --spp 2 --tonemap aces --exposure -1.5)
# OpenEXR output (--exr, --exr-half): the name and the options are checked in every build;
# a glint-render built without OpenEXR refuses --exr with status 2, saying why.
glint_cli_test(exr-not-exr STATUS 2
               STDERR "--exr writes an OpenEXR image: the file name must end in .exr, got 'out.jpg'"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --exr out.jpg OUTPUT out.png)
glint_cli_test(exr-half-alone STATUS 2 STDERR "--exr-half needs --exr FILE"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --exr-half OUTPUT out.png)
if(NOT TARGET glint::exr)
  glint_cli_test(exr-not-built STATUS 2
                 STDERR "this glint-render was built without OpenEXR \\(Debian: libopenexr-dev\\)"
                 ARGS ${glint_cli_scenes}/tiny.scene -o out.png --exr out.exr OUTPUT out.png)
else()
  glint_cli_test(exr-missing-directory STATUS 1 STDERR "nowhere/out.exr: directory .* does not exist"
                 ARGS ${glint_cli_scenes}/tiny.scene -o out.png --exr nowhere/out.exr
                 OUTPUT out.png)
  glint_cli_test(exr-is-checkpoint STATUS 1
                 STDERR "cannot write the checkpoint out.exr: it is also the image out.exr"
                 ARGS ${glint_cli_scenes}/tiny.scene -o out.png --exr out.exr --checkpoint out.exr
                 OUTPUT out.exr)
  # All four outputs at once: the most temporaries glint-render keeps for its signal handler.
  glint_cli_test(exr-renders STATUS 0 EXPECT_OUTPUT OUTPUT out.exr
                 ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.pfm --exr out.exr
                      --checkpoint out.ck --spp 2)

  # The EXR read back against the PFM of the same render (tests/cli/exr_check.cpp), and its
  # attributes.
  add_executable(glint-exr-check ${CMAKE_CURRENT_LIST_DIR}/exr_check.cpp)
  target_link_libraries(glint-exr-check PRIVATE glint::exr glint_project_options)
  function(glint_exr_cli_test name)
    cmake_parse_arguments(arg "" "STDERR" "ARGS;CHECK_ARGS;EXPECT" ${ARGN})
    string(REPLACE ";" "|" joined_args "${arg_ARGS}")
    string(REPLACE ";" "|" joined_check_args "${arg_CHECK_ARGS}")
    string(REPLACE ";" "|" joined_expect "${arg_EXPECT}")
    set(defines -DPROGRAM=$<TARGET_FILE:glint-render> "-DARGS=${joined_args}"
        -DCHECK=$<TARGET_FILE:glint-exr-check> "-DCHECK_ARGS=${joined_check_args}"
        "-DEXPECT=${joined_expect}" -DSCRATCH=${PROJECT_BINARY_DIR}/cli-test/${name})
    if(DEFINED arg_STDERR)
      list(APPEND defines "-DEXPECT_STDERR=${arg_STDERR}")
    endif()
    add_test(NAME "cli: ${name}" COMMAND ${CMAKE_COMMAND} ${defines}
             -P ${CMAKE_CURRENT_LIST_DIR}/exr_matches_pfm.cmake)
    set_tests_properties("cli: ${name}" PROPERTIES LABELS "cli;exr")
  endfunction()
  glint_exr_cli_test(exr-matches-pfm
    ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.pfm --exr out.exr --spp 3 --seed 7
         --threads 1
    EXPECT "pixel type: float" "pixels: identical to the PFM"
           "comments \\(string\\) = <glint-render [0-9]+\\.[0-9]+\\.[0-9]+ \\([a-z_]+, [a-z]+\\): .*tiny\\.scene, 3 of 3 samples per pixel, max depth 3, seed 7>"
           "glint/version \\(string\\) = <[0-9]+\\.[0-9]+\\.[0-9]+>"
           "glint/variant \\(string\\) = <[a-z_]+>"
           "glint/executionModel \\(string\\) = <[a-z]+>"
           "glint/scene \\(string\\) = <.*tiny\\.scene>"
           "glint/width \\(int\\) = <24>" "glint/height \\(int\\) = <16>"
           "glint/samplesPerPixel \\(int\\) = <3>" "glint/samplesPerPixelRequested \\(int\\) = <3>"
           "glint/maxDepth \\(int\\) = <3>" "glint/antialiasSigma \\(float\\) = <[0-9.]+>"
           "glint/seed \\(string\\) = <7>" "glint/threads \\(int\\) = <1>"
           "glint/renderSeconds \\(double\\) = <[0-9.e-]+>")
  glint_exr_cli_test(exr-half-matches-pfm
    ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.pfm --exr out.exr --exr-half --spp 2
         --width 40 --height 30 --max-depth 5 --seed 18446744073709551615
    CHECK_ARGS --half
    EXPECT "pixel type: half" "pixels: within half precision of the PFM"
           "glint/width \\(int\\) = <40>" "glint/maxDepth \\(int\\) = <5>"
           "glint/seed \\(string\\) = <18446744073709551615>")
  # A lamp of radiance 1e6: the half EXR holds 65504 there, and glint-render says so.
  glint_exr_cli_test(exr-half-clamps
    ARGS ${glint_cli_scenes}/bright-lamp.scene -o out.png --hdr out.pfm --exr out.exr --exr-half
    STDERR "warning: [0-9]+ channel values beyond the largest half were written to out\\.exr as 65504"
    CHECK_ARGS --half EXPECT "pixels: within half precision of the PFM")
  # Stopped early: the header says how many samples the image holds of those asked for.
  glint_exr_cli_test(exr-time-limit
    ARGS ${glint_cli_scenes}/tiny.scene -o out.png --hdr out.pfm --exr out.exr --spp 64
         --time-limit 0
    EXPECT "pixels: identical to the PFM" "glint/samplesPerPixel \\(int\\) = <1>"
           "glint/samplesPerPixelRequested \\(int\\) = <64>" " 1 of 64 samples per pixel")
endif()

# Each program names itself in its messages: the name it was built as (glint-render-report), or
# for a copy of glint-render named glint-render-SOMETHING, the name it was run as.
glint_cli_test(program-name-variant PROGRAM glint-render-report STATUS 2
               STDERR "^glint-render-report: unknown option '--frobnicate'.Run 'glint-render-report --help' for the options"
               ARGS ${glint_cli_scenes}/tiny.scene --frobnicate)
glint_cli_test(program-name-help PROGRAM glint-render-report STATUS 0
               STDOUT "^usage: glint-render-report SCENE \\[options\\]" ARGS --help)
set(glint_render_copy ${PROJECT_BINARY_DIR}/cli-test/copies/glint-render-nightly)
add_test(NAME "cli: program-name-copy-made"
         COMMAND ${CMAKE_COMMAND} -E copy $<TARGET_FILE:glint-render> ${glint_render_copy})
set_tests_properties("cli: program-name-copy-made" PROPERTIES LABELS cli
                     FIXTURES_SETUP glint_render_copy)
add_test(NAME "cli: program-name-copy"
         COMMAND ${CMAKE_COMMAND} -DPROGRAM=${glint_render_copy}
                 "-DARGS=${glint_cli_scenes}/tiny.scene|--frobnicate" -DEXPECT_STATUS=2
                 "-DEXPECT_STDERR=^glint-render-nightly: unknown option '--frobnicate'.Run 'glint-render-nightly --help'"
                 -DSCRATCH=${PROJECT_BINARY_DIR}/cli-test/program-name-copy
                 -P ${CMAKE_CURRENT_LIST_DIR}/run_cli.cmake)
set_tests_properties("cli: program-name-copy" PROPERTIES LABELS cli
                     FIXTURES_REQUIRED glint_render_copy)

# --stats-json (tests/cli/check_stats_json.cmake): the figures as JSON, written with the images:
# 24x16 pixels of tiny.scene at 3 samples each are 1152 samples; stopped by --time-limit 0, the
# first pass's 1 sample each, 384.
function(glint_cli_stats_test name)
  cmake_parse_arguments(arg "" "PROGRAM;STATUS" "ARGS;EXPECT" ${ARGN})
  string(REPLACE ";" "|" joined_args "${arg_ARGS}")
  string(REPLACE ";" "@@" joined_expect "${arg_EXPECT}")
  add_test(NAME "cli: ${name}"
           COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${arg_PROGRAM}> "-DARGS=${joined_args}"
                   "-DEXPECT=${joined_expect}" -DEXPECT_STATUS=${arg_STATUS}
                   -DSCRATCH=${PROJECT_BINARY_DIR}/cli-test/${name}
                   -P ${CMAKE_CURRENT_LIST_DIR}/check_stats_json.cmake)
  set_tests_properties("cli: ${name}" PROPERTIES LABELS cli)
endfunction()
glint_cli_stats_test(stats-json PROGRAM glint-render STATUS 0
  ARGS ${glint_cli_scenes}/tiny.scene -o out.png --spp 3 --threads 1 --seed 5 --max-depth 2
       --stats-json stats.json
  EXPECT "program=glint-render" "variant~^[a-z_]+$" "execution_model~^(wavefront|scalar)$"
         "simd~^(avx512|avx2|scalar)$" "paths_at_once~^(1|8|16)$" "scene~tiny\\.scene$"
         "output=out.png" "width=24" "height=16" "samples_per_pixel=3"
         "samples_per_pixel_requested=3" "passes_done=3" "pass_count=3" "max_depth=2" "seed=5"
         "ranks=1" "threads=1" "samples=1152" "rays~^[1-9][0-9]*$" "invalid_samples=0"
         "clamped_pixels=0" "complete=ON" "stopped_by=TYPE:NULL" "time_limit_reached=OFF"
         "version~^[0-9]+\\.[0-9]+\\.[0-9]+$")
glint_cli_stats_test(stats-json-time-limit PROGRAM glint-render-report STATUS 0
  ARGS ${glint_cli_scenes}/tiny.scene -o out.png --spp 64 --time-limit 0 --scalar
       --stats-json stats.json
  EXPECT "program=glint-render-report" "variant=report" "execution_model=scalar"
         "paths_at_once=1" "samples_per_pixel=1" "samples_per_pixel_requested=64"
         "passes_done=1" "pass_count=7" "samples=384" "complete=OFF" "time_limit_reached=ON")
glint_cli_test(stats-json-not-json STATUS 2
               STDERR "--stats-json writes JSON: the file name must end in .json, got 'stats.txt'"
               ARGS ${glint_cli_scenes}/tiny.scene --stats-json stats.txt)
# A failed run writes no figures, as it writes no image.
glint_cli_test(stats-json-failed-run STATUS 1 STDERR "overlapping-glass.scene:[0-9]+: error"
               ARGS ${glint_cli_scenes}/overlapping-glass.scene -o out.png --stats-json out.json
               OUTPUT out.json)
# --list-simd: the instruction sets glint-render holds that this CPU runs, narrowest first;
# with GLINT_SIMD_DISPATCH x86-64's (scalar) always, else the one it was compiled for.
if(GLINT_SIMD_DISPATCH)
  glint_cli_test(list-simd STATUS 0 STDOUT "^scalar\n(avx2\n(avx512\n)?)?$" ARGS --list-simd)
else()
  glint_cli_test(list-simd STATUS 0 STDOUT "^(scalar|avx2|avx512)\n$" ARGS --list-simd)
endif()

glint_cli_test(bad-time-limit STATUS 2 STDERR "--time-limit expects seconds from 0 to 1e9, got '-1'"
               ARGS ${glint_cli_scenes}/tiny.scene --time-limit -1)
glint_cli_test(bad-checkpoint-interval STATUS 2
               STDERR "--checkpoint-interval expects seconds from 0 to 1e9, got '1m'"
               ARGS ${glint_cli_scenes}/tiny.scene --checkpoint-interval 1m)
glint_cli_test(checkpoint-is-output STATUS 1
               STDERR "cannot write the checkpoint ./out.png: it is also the image out.png"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --checkpoint ./out.png OUTPUT out.png)
glint_cli_test(missing-checkpoint STATUS 1 STDERR "cannot resume from no-such.ck: No such file"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --resume no-such.ck OUTPUT out.png)
# Sizes beyond the pixel limit are option errors: refused before the scene is read (a missing
# scene would be status 1) when the options alone exceed it, after when the scene's size does.
glint_cli_test(pixel-limit STATUS 2 STDERR "--width 32768 --height 4096 exceeds 67108864 pixels"
               ARGS no-such.scene --width 32768 --height 4096)
glint_cli_test(pixel-limit-with-scene STATUS 2
               STDERR "tall.scene's image settings: image size 4096x32768 exceeds 67108864 pixels"
               ARGS ${glint_cli_scenes}/tall.scene --width 4096 -o out.png OUTPUT out.png)
glint_cli_test(quiet STATUS 0 STDERR "^$" STDOUT "^$" EXPECT_OUTPUT OUTPUT tiny.png
               ARGS ${glint_cli_scenes}/tiny.scene --quiet --threads 1)

# Progress lines and the summary on stderr, as a log gets them (stderr is a pipe here).
# 160 x 96 pixels (60 tiles), 3 samples each: 46080 samples, printed with %.3g.
function(glint_cli_progress_test name program variant)
  string(REPLACE ";" "|" joined_args "${ARGN}")
  set(summary "^${program} \\(${variant}, [a-z0-9]+, (one path at a time|[0-9]+ paths at once)\\): ")
  string(APPEND summary "[^ ]*tiny\\.scene -> out\\.png: 160x96, 3 spp, ")
  string(APPEND summary "depth 2 in [0-9]+\\.[0-9][0-9] s on [12] threads: 4\\.61e\\+04 samples, ")
  string(APPEND summary "[0-9]+\\.[0-9] Mrays/s$")
  add_test(NAME "cli: ${name}" COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${program}>
           -DSCENE=${glint_cli_scenes}/tiny.scene "-DARGS=${joined_args}" "-DSUMMARY=${summary}"
           -DSCRATCH=${PROJECT_BINARY_DIR}/cli-test/${name}
           -P ${CMAKE_CURRENT_LIST_DIR}/check_progress.cmake)
  set_tests_properties("cli: ${name}" PROPERTIES LABELS cli)
endfunction()
glint_cli_progress_test(progress-report glint-render-report "report, scalar"
                        -o out.png --width 160 --height 96 --spp 3 --max-depth 2 --threads 2)
glint_cli_progress_test(progress-default-variant glint-render "[a-z_]+, (wavefront|scalar)"
                        -o out.png --width 160 --height 96 --spp 3 --max-depth 2 --threads 1)

# Long renders (tests/cli/long_render_test.bash): the first SIGINT, SIGTERM or SIGHUP writes
# the image of the completed passes, a second one exits at once, and a supervisor's copies of
# one signal (to the process and its group: `timeout`) are one stop; planted symbolic links are
# never followed; all outputs or none; outputs refused before rendering; threads that cannot
# start; checkpoints resumed to the uninterrupted bytes (after SIGINT, or SIGKILL after a
# checkpoint between passes), checkpoints of other renders refused; --time-limit. On sky.scene,
# which glint-render renders with its default variant, the path tracer (the estimators' own
# programs run the checkpoint cases below). Status 77: the case cannot run here (a read-only
# directory does not stop root).
find_program(GLINT_BASH bash)
if(GLINT_BASH)
  foreach(case sigint sigterm sighup group_signal timeout second_signal sigint_quiet planted_symlinks
          hdr_fails_while_writing hdr_is_directory output_is_directory read_only_directory
          scene_is_output threads_fail checkpoint_resume checkpoint_after_kill resume_refused
          time_limit_zero huge_values checkpoint_fails_complete checkpoint_fails_time_limit
          checkpoint_fails_sigint checkpoint_directory_vanishes long_second_name
          checkpoint_exists stale_temporaries sigusr1 sigalrm sigxcpu repeated_sigxcpu
          progress_reader_closes out_of_memory)
    string(REPLACE "_" "-" name ${case})
    add_test(NAME "cli: ${name}"
             COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/long_render_test.bash ${case}
                     $<TARGET_FILE:glint-render> ${glint_cli_scenes}/sky.scene
                     ${PROJECT_BINARY_DIR}/cli-test/${name} $<TARGET_FILE:glint-render-report>)
    set_tests_properties("cli: ${name}" PROPERTIES LABELS cli SKIP_RETURN_CODE 77)
    if(case MATCHES "^(checkpoint_resume|checkpoint_after_kill|group_signal|repeated_sigxcpu)$")
      set_tests_properties("cli: ${name}" PROPERTIES LABELS "cli;long")
    endif()
    if(GLINT_SANITIZE)
      set_tests_properties("cli: ${name}" PROPERTIES ENVIRONMENT GLINT_LONG_RENDER_SIZE=160x120)
    endif()
  endforeach()
endif()

# glint-render's estimators: the path tracer where it sees all the light, vertex merging where a
# point light shines through glass (tiny.scene), --estimator to choose; a name it does not hold
# is refused, and a variant's own program takes no --estimator. Each estimator gives its own
# program's bytes, and a resumed render continues with the estimator of its checkpoint
# (tests/cli/estimator_test.bash).
string(REPLACE "_" "-" glint_default_dashed ${GLINT_DEFAULT_VARIANT})
glint_cli_test(estimator-auto-path-tracer STATUS 0
               STDERR "glint-render \\(${GLINT_DEFAULT_VARIANT}, "
               ARGS ${glint_cli_scenes}/sky.scene -o out.png --spp 2)
glint_cli_test(estimator-choose STATUS 0 STDERR "glint-render \\(${GLINT_DEFAULT_VARIANT}, "
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --spp 2
                    --estimator ${glint_default_dashed})
glint_cli_test(estimator-unknown STATUS 2
               STDERR "--estimator expects auto,? (or )?${glint_default_dashed}.*, got 'path'"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --estimator path)
glint_cli_test(estimator-in-variant-program PROGRAM glint-render-report STATUS 2
               STDERR "unknown option '--estimator'"
               ARGS ${glint_cli_scenes}/tiny.scene -o out.png --estimator report)
if("vcm" IN_LIST GLINT_BUILT_VARIANTS)
  glint_cli_test(estimator-auto-blind-spot STATUS 0 STDERR "glint-render \\(vcm, "
                 ARGS ${glint_cli_scenes}/tiny.scene -o out.png --spp 2)
endif()
if(GLINT_BASH)
  foreach(case same_bytes_as_own_program resume_follows_checkpoint)
    string(REPLACE "_" "-" name ${case})
    add_test(NAME "cli: estimator-${name}"
             COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/estimator_test.bash ${case}
                     $<TARGET_FILE:glint-render> $<TARGET_FILE_DIR:glint-render>
                     ${glint_cli_scenes}/tiny.scene ${PROJECT_BINARY_DIR}/cli-test/estimator-${name})
    set_tests_properties("cli: estimator-${name}" PROPERTIES LABELS cli)
  endforeach()
endif()

# Light tracing (glint-render-light-tracing): a scene with a background is one it cannot render
# (status 3, naming the line), a pixel filter without an area a setting it cannot use; its splats
# go into checkpoints, and a render stopped and resumed gives the uninterrupted bytes.
if(TARGET glint-render-light-tracing)
  glint_cli_test(light-tracing-background PROGRAM glint-render-light-tracing STATUS 3
                 STDERR "sky.scene:4: .*light tracing needs a black background"
                 ARGS ${glint_cli_scenes}/sky.scene -o out.png)
  glint_cli_test(light-tracing-pixel-centres PROGRAM glint-render-light-tracing STATUS 1
                 STDERR "light tracing needs a pixel filter with an area"
                 ARGS ${glint_cli_scenes}/pixel-centres.scene -o out.png)
  glint_cli_test(light-tracing-help PROGRAM glint-render-light-tracing STATUS 0
                 STDOUT "by light tracing" ARGS --help)
  if(GLINT_BASH)
    foreach(case checkpoint_resume checkpoint_after_kill)
      string(REPLACE "_" "-" name ${case})
      add_test(NAME "cli: light-tracing-${name}"
               COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/long_render_test.bash ${case}
                       $<TARGET_FILE:glint-render-light-tracing> ${glint_cli_scenes}/tiny.scene
                       ${PROJECT_BINARY_DIR}/cli-test/light-tracing-${name})
      # Each join of a light path to the camera lands on every pixel of the filter's footprint
      # (about 36 for the Gaussian), each a locked addition: a quarter of the pixels keeps the
      # three renders of each case near the others' time.
      set_tests_properties("cli: light-tracing-${name}" PROPERTIES LABELS "cli;long"
                           ENVIRONMENT GLINT_LONG_RENDER_SIZE=160x120)
    endforeach()
  endif()
endif()

# Bidirectional path tracing (glint-render-bidirectional) renders what light tracing cannot (a
# background, pixel centres); its splats go into checkpoints, and a render stopped and resumed
# gives the uninterrupted bytes.
if(TARGET glint-render-bidirectional)
  glint_cli_test(bidirectional-help PROGRAM glint-render-bidirectional STATUS 0
                 STDOUT "by bidirectional path tracing" ARGS --help)
  glint_cli_test(bidirectional-background PROGRAM glint-render-bidirectional STATUS 0
                 OUTPUT out.png EXPECT_OUTPUT ARGS ${glint_cli_scenes}/sky.scene -o out.png)
  glint_cli_test(bidirectional-pixel-centres PROGRAM glint-render-bidirectional STATUS 0
                 OUTPUT out.png EXPECT_OUTPUT ARGS ${glint_cli_scenes}/pixel-centres.scene -o out.png)
  if(GLINT_BASH)
    foreach(case checkpoint_resume)
      string(REPLACE "_" "-" name ${case})
      add_test(NAME "cli: bidirectional-${name}"
               COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/long_render_test.bash ${case}
                       $<TARGET_FILE:glint-render-bidirectional> ${glint_cli_scenes}/tiny.scene
                       ${PROJECT_BINARY_DIR}/cli-test/bidirectional-${name})
      # A sample follows two paths and joins them: a sixteenth of the pixels keeps the case's
      # three renders near the others' time.
      set_tests_properties("cli: bidirectional-${name}" PROPERTIES LABELS "cli;long"
                           ENVIRONMENT GLINT_LONG_RENDER_SIZE=80x60)
    endforeach()
  endif()
endif()

# Vertex connection and merging (glint-render-vcm): the same cases, its light phase included in
# the checkpointed passes.
if(TARGET glint-render-vcm)
  glint_cli_test(vcm-help PROGRAM glint-render-vcm STATUS 0
                 STDOUT "by vertex connection and merging" ARGS --help)
  glint_cli_test(vcm-background PROGRAM glint-render-vcm STATUS 0
                 OUTPUT out.png EXPECT_OUTPUT ARGS ${glint_cli_scenes}/sky.scene -o out.png)
  glint_cli_test(vcm-pixel-centres PROGRAM glint-render-vcm STATUS 0
                 OUTPUT out.png EXPECT_OUTPUT ARGS ${glint_cli_scenes}/pixel-centres.scene -o out.png)
  if(GLINT_BASH)
    add_test(NAME "cli: vcm-checkpoint-resume"
             COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/long_render_test.bash checkpoint_resume
                     $<TARGET_FILE:glint-render-vcm> ${glint_cli_scenes}/tiny.scene
                     ${PROJECT_BINARY_DIR}/cli-test/vcm-checkpoint-resume)
    set_tests_properties("cli: vcm-checkpoint-resume" PROPERTIES LABELS "cli;long"
                         ENVIRONMENT GLINT_LONG_RENDER_SIZE=80x60)
  endif()
endif()

# The execution model (tests/cli/execution_model_test.bash), on a scene glint-render renders with
# its default variant (a point light and no glass or mirror): --scalar renders a finite image of
# the right size; the default and --scalar agree statistically; a checkpoint of either model
# resumes with either to the uninterrupted bytes; a variant without the wavefront renderer
# accepts --scalar, which changes nothing. --help says what --scalar does for each kind of variant.
glint_cli_test(help-scalar STATUS 0
               STDOUT "--scalar +render with the scalar renderer.*execution model: wavefront \\(the default\\), or scalar with --scalar"
               ARGS --help)
glint_cli_test(help-scalar-report PROGRAM glint-render-report STATUS 0
               STDOUT "--scalar +accepted, and changes nothing.*execution model: scalar \\(this variant's only one\\)"
               ARGS --help)
if(GLINT_BASH)
  foreach(case scalar_renders models_agree resume_across_models scalar_changes_nothing
          forged_variant)
    string(REPLACE "_" "-" name ${case})
    add_test(NAME "cli: ${name}"
             COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/execution_model_test.bash ${case}
                     $<TARGET_FILE:glint-render> ${glint_cli_scenes}/sky.scene
                     ${PROJECT_BINARY_DIR}/cli-test/${name} $<TARGET_FILE:glint-render-report>
                     $<TARGET_FILE:glint-checkpoint-forge>)
    set_tests_properties("cli: ${name}" PROPERTIES LABELS cli)
  endforeach()
endif()

# The instruction sets (tests/cli/simd_test.bash): the same image bit for bit with every set this
# CPU runs, thread count and execution model, on a scene of the linear scan (tiny) and one of the
# BVH (120 random spheres); a set unknown, or that a program does not hold, refused. With QEMU's
# user-mode emulator (Debian: qemu-user, `scripts/install-deps --qemu`), glint-render also runs
# on emulated CPUs without AVX-512 (Haswell) and without AVX2 (Nehalem), choosing the widest set
# they have and giving the same image.
glint_cli_test(simd-unknown STATUS 2 STDERR "--simd expects auto, avx512, avx2 or scalar, got 'sse'"
               ARGS ${glint_cli_scenes}/tiny.scene --simd sse)
if(TARGET glint-render-report)
  # A set glint-render-report does not hold: scalar where it is compiled for this CPU's SIMD,
  # AVX-512 where it is compiled without SIMD kernels or for a baseline x86-64.
  if(GLINT_NATIVE AND NOT CMAKE_CXX_FLAGS MATCHES "GLINT_NO_SIMD")
    set(glint_simd_not_held scalar)
  else()
    set(glint_simd_not_held avx512)
  endif()
  glint_cli_test(simd-not-held PROGRAM glint-render-report STATUS 2
                 STDERR "--simd ${glint_simd_not_held}: this program \\(variant report\\) was compiled for [a-z0-9]+ only"
                 ARGS ${glint_cli_scenes}/tiny.scene --simd ${glint_simd_not_held})
endif()
if(GLINT_BASH AND GLINT_SIMD_DISPATCH)
  set(glint_simd_bvh_scene ${PROJECT_BINARY_DIR}/simd-bvh.scene)
  add_test(NAME "cli: simd-bvh-scene"
           COMMAND glint-random-scene --count 120 --min-radius 0.5 --max-radius 4 --seed 3
                   -o ${glint_simd_bvh_scene})
  set_tests_properties("cli: simd-bvh-scene" PROPERTIES LABELS cli FIXTURES_SETUP simd_bvh_scene)
  find_program(GLINT_QEMU qemu-x86_64)
  set(simd_cases same_image)
  if(GLINT_QEMU)
    list(APPEND simd_cases emulated_without_avx2 emulated_without_avx512 emulated_lacking_set)
  else()
    message(STATUS "glint: qemu-x86_64 not found (Debian: qemu-user): glint-render is not "
                   "tested on emulated CPUs without AVX2 and AVX-512")
  endif()
  foreach(case IN LISTS simd_cases)
    foreach(scene tiny bvh)
      if(scene STREQUAL tiny)
        set(scene_file ${glint_cli_scenes}/tiny.scene)
      else()
        set(scene_file ${glint_simd_bvh_scene})
      endif()
      string(REPLACE "_" "-" name "simd-${case}-${scene}")
      add_test(NAME "cli: ${name}"
               COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/simd_test.bash ${case}
                       $<TARGET_FILE:glint-render> ${scene_file}
                       ${PROJECT_BINARY_DIR}/cli-test/${name} ${GLINT_QEMU})
      set_tests_properties("cli: ${name}" PROPERTIES LABELS cli FIXTURES_REQUIRED simd_bvh_scene)
    endforeach()
  endforeach()
endif()

# The report's tree model refuses a scene whose rays per sample would explode, before it
# renders anything; the one-lobe default variant renders the same scene.
glint_cli_test(tree-work-refused PROGRAM glint-render-report STATUS 1
               STDERR "split-room.scene\\) split every ray.*Lower max_depth to 18"
               ARGS ${glint_cli_scenes}/split-room.scene -o out.png OUTPUT out.png)
glint_cli_test(tree-work-one-lobe STATUS 0 EXPECT_OUTPUT OUTPUT out.png
               ARGS ${glint_cli_scenes}/split-room.scene -o out.png)

# A shading kind the variant's policy lacks is rejected when the scene is loaded; the example
# program with its own policy renders the same scene.
set(glint_striped_scene ${PROJECT_SOURCE_DIR}/examples/custom_shading/striped.scene)
glint_cli_test(unsupported-shading STATUS 3
               STDERR "striped.scene:[0-9]+: error: shading 'custom' is not supported"
               ARGS ${glint_striped_scene} -o out.png OUTPUT out.png)
if(TARGET glint-custom-shading)
  glint_cli_test(custom-shading-example PROGRAM glint-custom-shading STATUS 0 EXPECT_OUTPUT
                 OUTPUT striped.png ARGS ${glint_striped_scene} striped.png 2)
endif()

# A rough or metal mirror is refused by a variant with the report's material only, naming the
# sphere's line; the default renders it.
set(glint_metals_scene ${PROJECT_SOURCE_DIR}/bench/scenes/metals.scene)
if(TARGET glint-render-report)
  glint_cli_test(unsupported-rough-metal PROGRAM glint-render-report STATUS 3
                 STDERR "metals.scene:[0-9]+: error: a rough or metal mirror or rough glass .mirror_roughness, metal, transparent_roughness. is not supported"
                 ARGS ${glint_metals_scene} -o out.png OUTPUT out.png)
endif()
glint_cli_test(rough-metal-renders STATUS 0 EXPECT_OUTPUT OUTPUT out.png
               STDERR "glint-render .fast,"
               ARGS ${glint_metals_scene} --width 24 --height 16 --spp 2 -o out.png)

# glint-random-scene's output file.
include(${CMAKE_CURRENT_LIST_DIR}/random_scene_test.cmake)
