# Every public header compiles on its own: one generated translation unit per header, built
# with the project's warnings as part of the normal build.
file(GLOB_RECURSE glint_public_headers RELATIVE ${PROJECT_SOURCE_DIR}/include CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/include/glint/*.hpp)
set(glint_header_check_sources)
foreach(header IN LISTS glint_public_headers)
  string(MAKE_C_IDENTIFIER ${header} name)
  set(source ${CMAKE_CURRENT_BINARY_DIR}/header_check/${name}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "#include \"${header}\"\n" @ONLY)
  list(APPEND glint_header_check_sources ${source})
endforeach()
add_library(glint-header-check OBJECT ${glint_header_check_sources})
target_link_libraries(glint-header-check PRIVATE glint::glint glint_project_options)
