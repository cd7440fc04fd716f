# Runs PROGRAM with ARGS ('|'-separated) in SCRATCH, where ARGS write --stats-json stats.json,
# and checks the JSON: each EXPECT entry ('@@'-separated: a regex may hold '|') is MEMBER=VALUE (CMake's reading of
# the member: a number's or string's text, ON or OFF for a boolean, TYPE:T for its type, e.g.
# TYPE:NULL), or MEMBER~REGEX. Then checks what the figures must satisfy whatever the run:
# samples = width x height x samples_per_pixel, mrays_per_second = rays / seconds / 1e6.
set(work ${SCRATCH})
string(REPLACE "|" ";" ARGS "${ARGS}")
string(REPLACE "@@" ";" EXPECT "${EXPECT}")
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
execute_process(COMMAND ${PROGRAM} ${ARGS} WORKING_DIRECTORY ${work}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL EXPECT_STATUS)
  message(FATAL_ERROR "exit status ${status}, expected ${EXPECT_STATUS}\nstderr: ${err}")
endif()
if(NOT EXISTS ${work}/stats.json)
  message(FATAL_ERROR "stats.json was not written\nstderr: ${err}")
endif()
file(READ ${work}/stats.json json)
string(JSON type ERROR_VARIABLE problem TYPE "${json}")
if(problem OR NOT type STREQUAL "OBJECT")
  message(FATAL_ERROR "stats.json is not a JSON object (${problem}):\n${json}")
endif()

foreach(entry IN LISTS EXPECT)
  if(entry MATCHES "^([a-z_]+)=TYPE:(.*)$")
    string(JSON got ERROR_VARIABLE problem TYPE "${json}" ${CMAKE_MATCH_1})
    set(want "${CMAKE_MATCH_2}")
  elseif(entry MATCHES "^([a-z_]+)=(.*)$")
    string(JSON got ERROR_VARIABLE problem GET "${json}" ${CMAKE_MATCH_1})
    set(want "${CMAKE_MATCH_2}")
  elseif(entry MATCHES "^([a-z_]+)~(.*)$")
    string(JSON got ERROR_VARIABLE problem GET "${json}" ${CMAKE_MATCH_1})
    if(problem OR NOT got MATCHES "${CMAKE_MATCH_2}")
      message(FATAL_ERROR "${CMAKE_MATCH_1} is '${got}', not matching '${CMAKE_MATCH_2}' ${problem}\n${json}")
    endif()
    continue()
  else()
    message(FATAL_ERROR "bad EXPECT entry '${entry}'")
  endif()
  if(problem OR NOT got STREQUAL want)
    message(FATAL_ERROR "${CMAKE_MATCH_1} is '${got}', expected '${want}' ${problem}\n${json}")
  endif()
endforeach()

# Figures that hold for every run, from the JSON's own members.
foreach(member width height samples_per_pixel samples rays seconds mrays_per_second)
  string(JSON ${member} ERROR_VARIABLE problem GET "${json}" ${member})
  if(problem)
    message(FATAL_ERROR "no member ${member}: ${problem}\n${json}")
  endif()
endforeach()
math(EXPR expected_samples "${width} * ${height} * ${samples_per_pixel}")
if(NOT samples EQUAL expected_samples)
  message(FATAL_ERROR "samples ${samples}, not width x height x spp = ${expected_samples}\n${json}")
endif()
# rays / seconds / 1e6 against the member, within its 9 significant digits: CMake's math has no
# floating point, awk has.
find_program(awk awk REQUIRED)
execute_process(COMMAND ${awk} -v r=${rays} -v s=${seconds} -v m=${mrays_per_second}
  "BEGIN { e = r / s * 1e-6; d = e - m; if (d < 0) d = -d; exit !(s > 0 && d <= 1e-6 * e + 1e-9) }"
  RESULT_VARIABLE mismatch)
if(NOT mismatch EQUAL 0)
  message(FATAL_ERROR "mrays_per_second ${mrays_per_second} is not rays / seconds / 1e6 "
                      "(${rays} / ${seconds} / 1e6)\n${json}")
endif()
