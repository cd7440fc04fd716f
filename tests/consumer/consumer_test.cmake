add_test(NAME "consumer: installed package and add_subdirectory"
  COMMAND ${CMAKE_COMMAND} -DGLINT_SOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DGLINT_BINARY_DIR=${PROJECT_BINARY_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake)
set_tests_properties("consumer: installed package and add_subdirectory" PROPERTIES
  LABELS "consumer;long" TIMEOUT 600)
