# Dependencies of the glint::glint interface target. Shared with glintConfig.cmake so that an
# installed glint finds exactly what the source tree found.
include(CMakeFindDependencyMacro)
include(GNUInstallDirs)
# In an installed glint's find_package, a missing GLM makes glint not found, as find_dependency
# does. In the source tree find_dependency would return from this file quietly and the build
# would fail later on an unknown glm::glm target, so the source tree says what is missing.
if(DEFINED CMAKE_FIND_PACKAGE_NAME)
  find_dependency(glm)
else()
  find_package(glm QUIET)
  if(NOT TARGET glm::glm)
    message(FATAL_ERROR "glint needs GLM's CMake package (Debian: apt install libglm-dev)")
  endif()
endif()
find_dependency(Threads)

# Debian's libstb-dev ships stb_image_write.h and a shared libstb with its implementation.
if(NOT TARGET glint::stb)
  find_path(GLINT_STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
  find_library(GLINT_STB_LIBRARY NAMES stb)
  if(NOT GLINT_STB_INCLUDE_DIR OR NOT GLINT_STB_LIBRARY)
    message(FATAL_ERROR "glint needs stb_image_write.h and libstb (Debian: apt install libstb-dev)")
  endif()
  add_library(glint::stb UNKNOWN IMPORTED)
  set_target_properties(glint::stb PROPERTIES
    IMPORTED_LOCATION "${GLINT_STB_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${GLINT_STB_INCLUDE_DIR}")
endif()
