# Installs glint into a scratch prefix, then builds and runs a separate consumer project
# against it (find_package), and again through add_subdirectory; then the example
# examples/render_scene against the installed package. Unoptimised (no build type):
# what is tested is that it compiles, links and runs, and its render is tiny.
cmake_minimum_required(VERSION 3.20)
set(work ${GLINT_BINARY_DIR}/consumer-test)
file(REMOVE_RECURSE ${work})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "command failed (${status}): ${ARGN}\n${out}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install ${GLINT_BINARY_DIR} --prefix ${work}/prefix)
run(${CMAKE_COMMAND} -S ${GLINT_SOURCE_DIR}/tests/consumer/project -B ${work}/installed
    -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_BUILD_TYPE=)
run(${CMAKE_COMMAND} --build ${work}/installed)
run(${work}/installed/consumer ${work}/installed.png)

run(${CMAKE_COMMAND} -S ${GLINT_SOURCE_DIR}/tests/consumer/project -B ${work}/subdirectory
    -DGLINT_SOURCE_DIR=${GLINT_SOURCE_DIR} -DCMAKE_BUILD_TYPE=)
run(${CMAKE_COMMAND} --build ${work}/subdirectory)
run(${work}/subdirectory/consumer ${work}/subdirectory.png)

# examples/render_scene, the README's example of using the library, against the installed
# package: it must build on its own and render a shipped scene.
run(${CMAKE_COMMAND} -S ${GLINT_SOURCE_DIR}/examples/render_scene -B ${work}/render-scene
    -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_BUILD_TYPE=)
run(${CMAKE_COMMAND} --build ${work}/render-scene)
run(${work}/render-scene/glint-render-scene ${GLINT_SOURCE_DIR}/scenes/fig1a-diffuse.scene
    ${work}/render-scene.png 1)
if(NOT EXISTS ${work}/render-scene.png)
  message(FATAL_ERROR "examples/render_scene wrote no image")
endif()
