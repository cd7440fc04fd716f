get_target_property(glm_includes glm::glm INTERFACE_INCLUDE_DIRECTORIES)
set(includes -I${PROJECT_SOURCE_DIR}/include)
foreach(dir ${glm_includes})
  list(APPEND includes -isystem ${dir})
endforeach()
add_test(NAME "compile-fail: a wrong policy names its concept"
  COMMAND ${CMAKE_COMMAND} -DCOMPILER=${CMAKE_CXX_COMPILER} "-DINCLUDES=${includes}"
          -DSOURCE=${CMAKE_CURRENT_LIST_DIR}/wrong_policy.cpp -DCONCEPT=FresnelModel
          -P ${CMAKE_CURRENT_LIST_DIR}/check_compile_fail.cmake)
set_tests_properties("compile-fail: a wrong policy names its concept" PROPERTIES LABELS compile)
