# Reads the list of named variants from include/glint/variants.hpp by compiling and running
# cmake/list_variants.cpp, so that no CMake file or script keeps a copy of it. Sets
#   GLINT_VARIANTS         the variant names, in the order of glint::variants::all
#   GLINT_DEFAULT_VARIANT  the variant glint-render renders with unless told otherwise
#   GLINT_WAVEFRONT_VARIANTS  the variants that also have the wavefront renderer
#   GLINT_EXECUTION_<name>    the class template of variant <name>'s Renderer execution model
#   GLINT_RENDER_ESTIMATORS   the variants glint-render holds (--estimator), the default first
#   GLINT_BLIND_SPOT_VARIANT  the one it chooses for a scene the path tracer is blind to
# and writes ${PROJECT_BINARY_DIR}/variants.tsv (the program's output) for bench/run-all.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/include/glint/variants.hpp ${PROJECT_SOURCE_DIR}/cmake/list_variants.cpp)
try_run(glint_list_variants_run glint_list_variants_compile
  ${PROJECT_BINARY_DIR}/list-variants ${PROJECT_SOURCE_DIR}/cmake/list_variants.cpp
  CMAKE_FLAGS "-DINCLUDE_DIRECTORIES=${PROJECT_SOURCE_DIR}/include"
  LINK_LIBRARIES glm::glm
  CXX_STANDARD 20 CXX_STANDARD_REQUIRED ON CXX_EXTENSIONS OFF
  COMPILE_OUTPUT_VARIABLE glint_list_variants_log
  RUN_OUTPUT_VARIABLE glint_variants_tsv)
if(NOT glint_list_variants_compile OR NOT glint_list_variants_run EQUAL 0)
  message(FATAL_ERROR "glint: cannot list the variants of include/glint/variants.hpp:\n"
    "${glint_list_variants_log}")
endif()
file(WRITE ${PROJECT_BINARY_DIR}/variants.tsv "${glint_variants_tsv}")
set(GLINT_VARIANTS)
set(GLINT_DEFAULT_VARIANT)
set(GLINT_WAVEFRONT_VARIANTS)
set(GLINT_RENDER_ESTIMATORS)
set(GLINT_BLIND_SPOT_VARIANT)
string(REPLACE "\n" ";" glint_variant_lines "${glint_variants_tsv}")
foreach(line IN LISTS glint_variant_lines)
  if(line MATCHES "^variant\t([a-z0-9_]+)\t")
    list(APPEND GLINT_VARIANTS ${CMAKE_MATCH_1})
  elseif(line MATCHES "^default\t([a-z0-9_]+)$")
    set(GLINT_DEFAULT_VARIANT ${CMAKE_MATCH_1})
  elseif(line MATCHES "^renderer\t([a-z0-9_]+)\tscalar\t([A-Za-z:]+)$")
    set(GLINT_EXECUTION_${CMAKE_MATCH_1} ${CMAKE_MATCH_2})
  elseif(line MATCHES "^renderer\t([a-z0-9_]+)\twavefront\t")
    list(APPEND GLINT_WAVEFRONT_VARIANTS ${CMAKE_MATCH_1})
  elseif(line MATCHES "^estimator\t([a-z0-9_]+)$")
    list(APPEND GLINT_RENDER_ESTIMATORS ${CMAKE_MATCH_1})
  elseif(line MATCHES "^blind_spot\t([a-z0-9_]+)$")
    set(GLINT_BLIND_SPOT_VARIANT ${CMAKE_MATCH_1})
  endif()
endforeach()
if(NOT GLINT_VARIANTS OR NOT GLINT_DEFAULT_VARIANT)
  message(FATAL_ERROR "glint: cmake/list_variants.cpp printed no variants:\n${glint_variants_tsv}")
endif()
