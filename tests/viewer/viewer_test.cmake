# glint-compare's page in headless Chromium, and glint-compare's refusals (label `viewer`):
# tests/viewer/viewer_test.bash. glint-compare is built in bench/ and the renderers in
# apps/, so both must be on; the targets are named through generator expressions because
# bench/ is added after tests/.
# The page's script, which no build compiles, parsed by node --check: needs only the source.
add_test(NAME "viewer: page script parses"
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/page_script_test.sh
                 ${PROJECT_SOURCE_DIR}/bench/compare_page.js)
set_tests_properties("viewer: page script parses" PROPERTIES LABELS viewer SKIP_RETURN_CODE 77)

if(NOT (GLINT_BUILD_BENCHMARKS AND GLINT_BUILD_PROGRAMS))
  message(STATUS "glint: no viewer tests (they need GLINT_BUILD_BENCHMARKS and "
                 "GLINT_BUILD_PROGRAMS)")
  return()
endif()
find_program(GLINT_BASH bash)
if(NOT GLINT_BASH)
  message(STATUS "glint: no bash, so no viewer tests")
  return()
endif()

# Reads a screenshot with stb_image, whose implementation Debian's libstb contains.
add_executable(glint-viewer-screenshot-check ${CMAKE_CURRENT_LIST_DIR}/screenshot_check.cpp)
target_link_libraries(glint-viewer-screenshot-check PRIVATE glint::glint glint_project_options)

foreach(case page keys missing-image errors exr)
  add_test(NAME "viewer: ${case}"
           COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/viewer_test.bash ${case}
                   ${PROJECT_BINARY_DIR}/viewer-test/${case} ${PROJECT_SOURCE_DIR}
                   $<TARGET_FILE:glint-render-report> $<TARGET_FILE:glint-render-fast>
                   $<TARGET_FILE:glint-compare> $<TARGET_FILE:glint-viewer-screenshot-check>)
  # 77: Chromium is missing (or, for `exr`, the build has no OpenEXR); ctest reports the test
  # as skipped. One browser at a time: each takes a core and a few hundred MB, and two at once
  # beside the rest of the suite could run past the timeout on a two-core machine.
  set_tests_properties("viewer: ${case}" PROPERTIES LABELS viewer SKIP_RETURN_CODE 77 TIMEOUT 120
                       RESOURCE_LOCK glint_browser)
endforeach()
