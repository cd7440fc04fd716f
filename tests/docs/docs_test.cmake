# Checks of the documentation against the code (label `docs`).
#
# - The generated tables of README.md and docs/*.md (the named variants, every table of figures)
#   must be what scripts/update-docs writes from include/glint/variants.hpp, as this build's
#   variants.tsv has it, and from bench/results. On failure the test prints the difference and
#   the command that rewrites them.
# - docs/glint-render.md must have a row for every option of `glint-render --help`, and
#   docs/cluster.md for every option glint-render-mpi adds; docs/scene-format.md must document
#   every statement, key and shading kind the scene reader accepts (from the reader's own
#   tables), and its complete example must be valid and use them all
#   (tests/docs/reference_test.bash).
find_program(GLINT_BASH bash)
if(NOT GLINT_BASH)
  message(STATUS "glint: no bash, so no docs test")
  return()
endif()
add_test(NAME "docs: generated tables match variants.hpp and bench/results"
         COMMAND ${GLINT_BASH} ${PROJECT_SOURCE_DIR}/scripts/update-docs --check
                 --build-dir ${PROJECT_BINARY_DIR})
set_tests_properties("docs: generated tables match variants.hpp and bench/results"
                     PROPERTIES LABELS docs)

# glint_docs_reference_test(ID NAME ARGS...): reference_test.bash ARGS in a scratch directory.
function(glint_docs_reference_test id name)
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/docs-${id})
  file(MAKE_DIRECTORY ${dir})
  add_test(NAME "docs: ${name}" COMMAND ${GLINT_BASH}
           ${PROJECT_SOURCE_DIR}/tests/docs/reference_test.bash ${ARGN} WORKING_DIRECTORY ${dir})
  set_tests_properties("docs: ${name}" PROPERTIES LABELS docs)
endfunction()

add_executable(glint-scene-format-keys ${CMAKE_CURRENT_LIST_DIR}/scene_format_keys.cpp)
target_link_libraries(glint-scene-format-keys PRIVATE glint::glint glint_test_options)
glint_docs_reference_test(scene-format "docs/scene-format.md documents what the scene reader accepts"
  scene ${PROJECT_SOURCE_DIR}/docs/scene-format.md $<TARGET_FILE:glint-scene-format-keys>)
if(TARGET glint-render)
  glint_docs_reference_test(glint-render "docs/glint-render.md documents every option of glint-render"
    options ${PROJECT_SOURCE_DIR}/docs/glint-render.md $<TARGET_FILE:glint-render>)
endif()
if(TARGET glint-render-mpi)
  glint_docs_reference_test(cluster "docs/cluster.md documents the options glint-render-mpi adds"
    options ${PROJECT_SOURCE_DIR}/docs/cluster.md $<TARGET_FILE:glint-render-mpi>
    $<TARGET_FILE:glint-render>)
endif()
