# A program that must not compile: building it is the test, and it passes only if the build
# fails with a message naming the violated concept.
add_executable(glint-compile-fail-wrong-policy EXCLUDE_FROM_ALL
  ${CMAKE_CURRENT_LIST_DIR}/wrong_policy.cpp)
target_link_libraries(glint-compile-fail-wrong-policy PRIVATE glint::glint)
add_test(NAME "compile-fail: a wrong policy names its concept"
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DTARGET=glint-compile-fail-wrong-policy -DCONCEPT=Fresnel
          -P ${CMAKE_CURRENT_LIST_DIR}/expect_build_failure.cmake)
set_tests_properties("compile-fail: a wrong policy names its concept" PROPERTIES LABELS compile)

# The wavefront renderer follows one path per sample: the report's tree model is refused with
# WavefrontExecution's one message.
add_executable(glint-compile-fail-wavefront-tree EXCLUDE_FROM_ALL
  ${CMAKE_CURRENT_LIST_DIR}/wavefront_tree.cpp)
target_link_libraries(glint-compile-fail-wavefront-tree PRIVATE glint::glint)
add_test(NAME "compile-fail: the wavefront renderer refuses the tree model"
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DTARGET=glint-compile-fail-wavefront-tree
          "-DMESSAGE=WavefrontRenderer renders chain configurations only"
          -P ${CMAKE_CURRENT_LIST_DIR}/expect_build_failure.cmake)
set_tests_properties("compile-fail: the wavefront renderer refuses the tree model"
  PROPERTIES LABELS compile)

# A material model's Bsdf is checked where an estimator uses it: one lacking a member fails with
# the static assertion that names the Bsdf concept.
add_executable(glint-compile-fail-incomplete-bsdf EXCLUDE_FROM_ALL
  ${CMAKE_CURRENT_LIST_DIR}/incomplete_bsdf.cpp)
target_link_libraries(glint-compile-fail-incomplete-bsdf PRIVATE glint::glint)
add_test(NAME "compile-fail: a material model's incomplete Bsdf names the concept"
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DTARGET=glint-compile-fail-incomplete-bsdf "-DMESSAGE=Bsdf<"
          -P ${CMAKE_CURRENT_LIST_DIR}/expect_build_failure.cmake)
set_tests_properties("compile-fail: a material model's incomplete Bsdf names the concept"
  PROPERTIES LABELS compile)
