# Fails, naming the files and one symbol of each, if an object file of the build outside
# glint-renderers defines a member of a named variant's renderer, execution model, path tracer
# or estimator: that file compiled a renderer that glint-renderers already holds. The generated
# renderer files themselves (BUILD/renderers/*.cpp) are the one place each renderer is compiled,
# in glint-renderers and, for glint-render's instruction sets, once per set (apps/CMakeLists.txt,
# glint_simd_objects: each set's renderers live in that set's namespace). The examples
# (examples/) and the consumer test are exempt: they are programs of a library user, who
# compiles the renderers they use. OBJECTS, where given, are the files to check instead of the
# build's (the test's positive control: the planted offender, tests/build/planted_renderer.cpp,
# which the check of the build leaves out). LIBRARY, where given, is glint-renderers: a wavefront
# renderer at a shading width it does not hold (glint-variants-bench measures widths 1 and 8
# beside the default) is not compiled again, so it is left out.
cmake_minimum_required(VERSION 3.20)
if(DEFINED OBJECTS)
  set(objects ${OBJECTS})
else()
  file(GLOB_RECURSE objects ${BUILD_DIR}/*.o)
  list(FILTER objects EXCLUDE REGEX
       "/CMakeFiles/(glint-renderers|glint-planted-renderer)\\.dir/|/renderers/[a-z0-9_]+\\.cpp\\.o$|/consumer-test/|/examples/[a-z_]+/CMakeFiles/")
endif()
if(NOT objects)
  message(FATAL_ERROR "no object files under ${BUILD_DIR}: build first")
endif()
# A defined symbol (text, data, weak or unique) whose owner is one of those class templates of a
# type of glint::variants, both inside the inline namespace of the instruction set the file was
# compiled for (glint::isa_avx2::Renderer<glint::isa_avx2::variants::fast, ...>). Templates of
# the tests (a test case per renderer type) only name the type.
set(owner "(Renderer|ScalarExecution|WavefrontExecution|PathTracer|ChainEstimator|TreeEstimator)")
set(isa "(isa_[a-z0-9_]+::)?")
set(pattern "^[0-9a-f]+ [TtDdRrBbWwVvu] glint::${isa}${owner}<glint::${isa}variants::")
set(wavefront_instance
    "WavefrontExecution<glint::${isa}variants::[a-z0-9_]+, [0-9]+>")
set(held_wavefronts)
if(DEFINED LIBRARY)
  execute_process(COMMAND ${NM} -C --defined-only ${LIBRARY} OUTPUT_VARIABLE library_symbols
                  RESULT_VARIABLE status ERROR_QUIET)
  string(REGEX MATCHALL "${wavefront_instance}" held_wavefronts "${library_symbols}")
  list(REMOVE_DUPLICATES held_wavefronts)
  if(NOT status EQUAL 0 OR NOT held_wavefronts)
    message(FATAL_ERROR "${NM} found no wavefront renderer in ${LIBRARY}")
  endif()
endif()
set(offenders)
set(read 0)
foreach(object IN LISTS objects)
  execute_process(COMMAND ${NM} -C --defined-only ${object} OUTPUT_VARIABLE symbols
                  RESULT_VARIABLE status ERROR_QUIET)
  if(NOT status EQUAL 0)
    continue()  # not an object nm reads (a precompiled header's companion, say)
  endif()
  math(EXPR read "${read} + 1")
  string(REPLACE "\n" ";" lines "${symbols}")
  foreach(line IN LISTS lines)
    if(line MATCHES "${pattern}" AND DEFINED LIBRARY)
      string(REGEX MATCHALL "${wavefront_instance}" wavefronts "${line}")
      list(REMOVE_ITEM wavefronts ${held_wavefronts})
      if(wavefronts)
        continue()  # a width glint-renderers does not hold
      endif()
    endif()
    if(line MATCHES "${pattern}")
      if(DEFINED OBJECTS)
        set(name ${object})
      else()
        file(RELATIVE_PATH name ${BUILD_DIR} ${object})
      endif()
      list(APPEND offenders "${name}: ${line}")
      break()
    endif()
  endforeach()
endforeach()
if(read EQUAL 0)
  message(FATAL_ERROR "${NM} read none of the object files: nothing was checked")
endif()
if(offenders)
  list(JOIN offenders "\n  " text)
  message(FATAL_ERROR "these files compile a named variant's renderer again instead of linking "
    "glint-renderers (include glint_renderers.hpp):\n  ${text}")
endif()
message(STATUS "${read} object files checked: the named renderers are compiled once")
