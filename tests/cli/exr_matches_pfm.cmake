# Renders with glint-render (PROGRAM, ARGS a '|'-joined list, writing out.exr and out.pfm in a
# scratch directory), then checks with glint-exr-check (CHECK, CHECK_ARGS '|'-joined) that the
# EXR holds the PFM's pixels, and that its report matches each regex of EXPECT ('|'-joined).
set(work ${SCRATCH})
string(REPLACE "|" ";" ARGS "${ARGS}")
string(REPLACE "|" ";" CHECK_ARGS "${CHECK_ARGS}")
string(REPLACE "|" ";" EXPECT "${EXPECT}")
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
execute_process(COMMAND ${PROGRAM} ${ARGS} WORKING_DIRECTORY ${work}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "glint-render: exit status ${status}\nstdout: ${out}\nstderr: ${err}")
endif()
if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "glint-render's stderr does not match '${EXPECT_STDERR}':\n${err}")
endif()
execute_process(COMMAND ${CHECK} out.exr out.pfm ${CHECK_ARGS} WORKING_DIRECTORY ${work}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "glint-exr-check: exit status ${status}\nstdout: ${out}\nstderr: ${err}")
endif()
foreach(regex IN LISTS EXPECT)
  if(NOT out MATCHES "${regex}")
    message(FATAL_ERROR "glint-exr-check's report does not match '${regex}':\n${out}")
  endif()
endforeach()
