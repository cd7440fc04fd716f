# Checks of the build itself (label `build`).
#
# - Each named renderer is compiled once: no object file outside glint-renderers defines a
#   function of a named variant's renderer, execution model, path tracer or estimator. (A file
#   that renders with a named variant without including glint_renderers.hpp compiles the whole
#   renderer again, silently; this is what finds it.)
# - Every test has a timeout, so that a hang fails that test instead of stalling the run.
add_test(NAME "build: each named renderer is compiled once, in glint-renderers"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DNM=${CMAKE_NM}
                 -P ${CMAKE_CURRENT_LIST_DIR}/renderers_compiled_once.cmake)
add_test(NAME "build: every test has a timeout"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DCTEST=${CMAKE_CTEST_COMMAND}
                 -P ${CMAKE_CURRENT_LIST_DIR}/test_timeouts.cmake)
set_tests_properties("build: each named renderer is compiled once, in glint-renderers"
                     "build: every test has a timeout" PROPERTIES LABELS build)
