# Every public header compiles on its own: one generated translation unit per header, built
# with the project's warnings. Not part of the default build (it is parsing alone, 78 files of
# it): the test `headers: each public header compiles on its own` builds it.
file(GLOB_RECURSE glint_public_headers RELATIVE ${PROJECT_SOURCE_DIR}/include CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/include/glint/*.hpp)
set(glint_header_check_sources)
foreach(header IN LISTS glint_public_headers)
  string(MAKE_C_IDENTIFIER ${header} name)
  set(source ${CMAKE_CURRENT_BINARY_DIR}/header_check/${name}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "#include \"${header}\"\n" @ONLY)
  list(APPEND glint_header_check_sources ${source})
endforeach()
add_library(glint-header-check OBJECT EXCLUDE_FROM_ALL ${glint_header_check_sources})
target_link_libraries(glint-header-check PRIVATE glint::glint glint_project_options)
add_test(NAME "headers: each public header compiles on its own"
         COMMAND ${CMAKE_COMMAND} --build ${PROJECT_BINARY_DIR} --target glint-header-check)
set_tests_properties("headers: each public header compiles on its own" PROPERTIES
  LABELS "headers;long" TIMEOUT 900)
