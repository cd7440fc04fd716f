add_test(NAME "consumer: installed package and add_subdirectory"
  COMMAND ${CMAKE_COMMAND} -DGLINT_SOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DGLINT_BINARY_DIR=${PROJECT_BINARY_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake)
set_tests_properties("consumer: installed package and add_subdirectory" PROPERTIES
  LABELS "consumer;long" TIMEOUT 600)

# glint::multiply_add_is_fused, compiled as a consumer without glint's CMake target would:
# with -ffp-contract=fast it must see the fused multiply-add, with =off not.
add_test(NAME "consumer: multiply_add_is_fused sees -ffp-contract"
  COMMAND ${CMAKE_COMMAND} -DCXX=${CMAKE_CXX_COMPILER} -DGLINT_SOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DWORK_DIR=${PROJECT_BINARY_DIR}/consumer-test
          -P ${CMAKE_CURRENT_LIST_DIR}/fp_contract_probe.cmake)
set_tests_properties("consumer: multiply_add_is_fused sees -ffp-contract" PROPERTIES
  LABELS consumer SKIP_REGULAR_EXPRESSION "SKIPPED:")
