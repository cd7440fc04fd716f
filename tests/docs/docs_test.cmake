# Checks of the documentation against the code (label `docs`).
#
# The README's generated tables (the named variants, the benchmark summary) must be what
# scripts/update-readme writes from include/glint/variants.hpp, as this build's variants.tsv
# has it, and bench/results/variants.md. On failure the test prints the difference and the
# command that rewrites them.
find_program(GLINT_BASH bash)
if(NOT GLINT_BASH)
  message(STATUS "glint: no bash, so no docs test")
  return()
endif()
add_test(NAME "docs: README variant tables match variants.hpp"
         COMMAND ${GLINT_BASH} ${PROJECT_SOURCE_DIR}/scripts/update-readme --check
                 --build-dir ${PROJECT_BINARY_DIR})
set_tests_properties("docs: README variant tables match variants.hpp" PROPERTIES LABELS docs)
