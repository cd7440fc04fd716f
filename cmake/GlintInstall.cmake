include(CMakePackageConfigHelpers)
install(TARGETS glint EXPORT glintTargets)
install(DIRECTORY include/glint DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set(GLINT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/glint)
install(EXPORT glintTargets NAMESPACE glint:: DESTINATION ${GLINT_CMAKE_DIR})
configure_package_config_file(cmake/glintConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/glintConfig.cmake INSTALL_DESTINATION ${GLINT_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/glintConfigVersion.cmake
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES
  ${CMAKE_CURRENT_BINARY_DIR}/glintConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/glintConfigVersion.cmake
  cmake/GlintDependencies.cmake
  DESTINATION ${GLINT_CMAKE_DIR})
