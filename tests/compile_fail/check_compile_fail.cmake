# Compiles SOURCE and passes only if compilation fails with a message naming CONCEPT.
execute_process(COMMAND ${COMPILER} -std=c++20 -fsyntax-only ${INCLUDES} ${SOURCE}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(status EQUAL 0)
  message(FATAL_ERROR "${SOURCE} compiled, but it must be rejected")
endif()
if(NOT out MATCHES "${CONCEPT}")
  message(FATAL_ERROR "${SOURCE} failed without naming ${CONCEPT}:\n${out}")
endif()
string(LENGTH "${out}" length)
message(STATUS "rejected as expected (${length} characters of diagnostics)")
