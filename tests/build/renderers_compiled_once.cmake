# Fails, naming the files and one symbol of each, if an object file of the build outside
# glint-renderers defines a member of a named variant's renderer, execution model, path tracer
# or estimator: that file compiled a renderer that glint-renderers already holds. The examples
# (examples/) and the consumer test are exempt: they are programs of a library user, who
# compiles the renderers they use.
cmake_minimum_required(VERSION 3.20)
file(GLOB_RECURSE objects ${BUILD_DIR}/*.o)
list(FILTER objects EXCLUDE REGEX "/CMakeFiles/glint-renderers\\.dir/|/consumer-test/|/examples/[a-z_]+/CMakeFiles/")
if(NOT objects)
  message(FATAL_ERROR "no object files under ${BUILD_DIR}: build first")
endif()
# A defined symbol (text, weak or unique) whose owner is one of those class templates of a type of
# glint::variants. Templates of the tests (a test case per renderer type) only name the type.
set(owner "(Renderer|ScalarExecution|WavefrontExecution|PathTracer|ChainEstimator|TreeEstimator)")
set(pattern "^[0-9a-f]+ [TtWwVvu] glint::${owner}<glint::variants::")
set(offenders)
foreach(object IN LISTS objects)
  execute_process(COMMAND ${NM} -C --defined-only ${object} OUTPUT_VARIABLE symbols
                  RESULT_VARIABLE status ERROR_QUIET)
  if(NOT status EQUAL 0)
    continue()  # not an object nm reads (a precompiled header's companion, say)
  endif()
  string(REPLACE "\n" ";" lines "${symbols}")
  foreach(line IN LISTS lines)
    if(line MATCHES "${pattern}")
      file(RELATIVE_PATH name ${BUILD_DIR} ${object})
      list(APPEND offenders "${name}: ${line}")
      break()
    endif()
  endforeach()
endforeach()
list(LENGTH objects count)
if(offenders)
  list(JOIN offenders "\n  " text)
  message(FATAL_ERROR "these files compile a named variant's renderer again instead of linking "
    "glint-renderers (include glint_renderers.hpp):\n  ${text}")
endif()
message(STATUS "${count} object files checked: the named renderers are compiled once")
