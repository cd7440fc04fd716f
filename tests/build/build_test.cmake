# Checks of the build itself (label `build`).
#
# - Each named renderer is compiled once: no object file outside glint-renderers defines a
#   function of a named variant's renderer, execution model, path tracer or estimator. (A file
#   that renders with a named variant without including glint_renderers.hpp compiles the whole
#   renderer again, silently; this is what finds it.)
# - Every test has a timeout, so that a hang fails that test instead of stalling the run.
add_test(NAME "build: each named renderer is compiled once, in glint-renderers"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DNM=${CMAKE_NM}
                 -DLIBRARY=$<TARGET_FILE:glint-renderers>
                 -P ${CMAKE_CURRENT_LIST_DIR}/renderers_compiled_once.cmake)
add_test(NAME "build: every test has a timeout"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DCTEST=${CMAKE_CTEST_COMMAND}
                 -P ${CMAKE_CURRENT_LIST_DIR}/test_timeouts.cmake)
set_tests_properties("build: each named renderer is compiled once, in glint-renderers"
                     "build: every test has a timeout" PROPERTIES LABELS build)

# The positive controls: each check above run on a planted offender, where it must fail with its
# message. A file that compiles a named variant's renderer member (planted_renderer.cpp, compiled
# as glint's programs are, and left out of the check of the build):
add_library(glint-planted-renderer OBJECT ${CMAKE_CURRENT_LIST_DIR}/planted_renderer.cpp)
target_link_libraries(glint-planted-renderer PRIVATE glint::glint glint_project_options)
add_test(NAME "build: a planted renderer is found"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DNM=${CMAKE_NM}
                 "-DOBJECTS=$<TARGET_OBJECTS:glint-planted-renderer>"
                 -P ${CMAKE_CURRENT_LIST_DIR}/renderers_compiled_once.cmake)
set_tests_properties("build: a planted renderer is found" PROPERTIES
  PASS_REGULAR_EXPRESSION
    "compile a named variant's renderer again.*planted_renderer\\.cpp\\.o: [0-9a-f]+ u glint::(isa_[a-z0-9_]+::)?ScalarExecution<")
# A test directory with one test that has a timeout and one that has none:
set(glint_untimed_dir ${CMAKE_CURRENT_BINARY_DIR}/untimed-test)
file(WRITE ${glint_untimed_dir}/CTestTestfile.cmake
     "add_test(timed \"${CMAKE_COMMAND}\" -E true)\n"
     "set_tests_properties(timed PROPERTIES TIMEOUT 5)\n"
     "add_test(untimed \"${CMAKE_COMMAND}\" -E true)\n")
add_test(NAME "build: a planted test without a timeout is found"
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${glint_untimed_dir} -DCTEST=${CMAKE_CTEST_COMMAND}
                 -P ${CMAKE_CURRENT_LIST_DIR}/test_timeouts.cmake)
set_tests_properties("build: a planted test without a timeout is found" PROPERTIES
  PASS_REGULAR_EXPRESSION "tests without a TIMEOUT property:[ \n]+untimed"
  FAIL_REGULAR_EXPRESSION "[ \n]timed")
set_tests_properties("build: a planted renderer is found"
                     "build: a planted test without a timeout is found" PROPERTIES LABELS build)
