# Builds TARGET in BUILD_DIR; passes only if the build fails with a message matching CONCEPT.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(status EQUAL 0)
  message(FATAL_ERROR "${TARGET} compiled, but it must be rejected")
endif()
if(NOT out MATCHES "${CONCEPT}")
  message(FATAL_ERROR "${TARGET} failed without naming ${CONCEPT}:\n${out}")
endif()
