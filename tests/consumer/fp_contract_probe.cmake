# glint::multiply_add_is_fused (glint/fp_contract.hpp) against the flags that decide it: the probe
# program (fp_contract_probe.cpp) compiled for a CPU with FMA (x86-64-v3) with -ffp-contract=off,
# as glint's CMake target compiles, must say "separate"; with -ffp-contract=fast, as GCC compiles
# a program that includes the headers without the target, "fused". Skipped (the line "SKIPPED:",
# the test's SKIP_REGULAR_EXPRESSION) where this CPU has no FMA to run the program on.
cmake_minimum_required(VERSION 3.20)
file(READ /proc/cpuinfo cpuinfo)
if(NOT cpuinfo MATCHES "[ \t]fma[ \n]")
  message("SKIPPED: this CPU has no FMA, so no multiply-add can be fused")
  return()
endif()
file(MAKE_DIRECTORY ${WORK_DIR})
foreach(contract off fast)
  set(program ${WORK_DIR}/probe-${contract})
  execute_process(
    COMMAND ${CXX} -std=c++20 -O2 -march=x86-64-v3 -ffp-contract=${contract} -Wall -Wextra
            -Wpedantic -Wshadow -Werror -I${GLINT_SOURCE_DIR}/include
            ${CMAKE_CURRENT_LIST_DIR}/fp_contract_probe.cpp -o ${program}
    RESULT_VARIABLE status ERROR_VARIABLE errors)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "compiling the probe with -ffp-contract=${contract} failed:\n${errors}")
  endif()
  execute_process(COMMAND ${program} OUTPUT_VARIABLE answer OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE status)
  set(${contract}_answer "${answer}")
endforeach()
if(NOT off_answer STREQUAL "separate" OR NOT fast_answer STREQUAL "fused")
  message(FATAL_ERROR "multiply_add_is_fused: '${off_answer}' with -ffp-contract=off (expected "
                      "separate), '${fast_answer}' with -ffp-contract=fast (expected fused)")
endif()
message(STATUS "multiply_add_is_fused: separate with -ffp-contract=off, fused with =fast")
