# Builds TARGET in BUILD_DIR; passes only if the build fails with the expected diagnosis:
#  - CONCEPT: a message that says the concept is not satisfied (GCC: "the satisfaction of
#    'CONCEPT<...>'", clang: "does not satisfy 'CONCEPT'"), not merely one that mentions it;
#  - MESSAGE: a message (a static_assert's) containing this text.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(status EQUAL 0)
  message(FATAL_ERROR "${TARGET} compiled, but it must be rejected")
endif()
if(DEFINED CONCEPT AND NOT out MATCHES "satisf[a-z]*( of)? [^a-zA-Z ]+${CONCEPT}[^a-zA-Z]")
  message(FATAL_ERROR "${TARGET} failed without naming ${CONCEPT}:\n${out}")
endif()
if(DEFINED MESSAGE)
  string(FIND "${out}" "${MESSAGE}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${TARGET} failed without saying '${MESSAGE}':\n${out}")
  endif()
endif()
