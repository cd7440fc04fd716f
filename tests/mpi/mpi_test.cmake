# glint-render-mpi under mpirun (label `mpi`), where MPI was found and glint-render-mpi built:
# the bytes of glint-render's image for 1, 2 and 3 ranks (and with --scalar, and with --simd
# scalar), every estimator's (their splats summed over the ranks, vertex merging's light phase
# run by each), a scene with image textures, ranks that read different images refused,
# checkpoints resumed across the two programs, a scene error printed once, ranks
# started with different settings refused, a bad option, a rank killed mid-render, and a stop by
# a signal (tests/mpi/mpi_render_test.bash). Ranks outnumber the cores with --oversubscribe; CI
# runs as root, which Open MPI refuses unless told otherwise.
if(NOT TARGET glint-render-mpi OR NOT MPIEXEC_EXECUTABLE)
  return()
endif()
find_program(GLINT_BASH bash)
if(NOT GLINT_BASH)
  return()
endif()

# glint_mpi_test(NAME CASE [ARGS...]): the script's case CASE with ARGS.
string(REPLACE "_" "-" glint_mpi_default ${GLINT_DEFAULT_VARIANT})
function(glint_mpi_test name case)
  add_test(NAME "mpi: ${name}"
           COMMAND ${GLINT_BASH} ${CMAKE_CURRENT_LIST_DIR}/mpi_render_test.bash ${case}
                   ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:glint-render-mpi>
                   $<TARGET_FILE:glint-render> ${glint_mpi_default} ${PROJECT_SOURCE_DIR}
                   ${PROJECT_BINARY_DIR}/mpi-test/${name} ${ARGN})
  # Root is refused unless allowed; in a container without ptrace rights, Open MPI's
  # shared-memory single copy (CMA) fails: plain copies are as good for these small renders.
  set_tests_properties("mpi: ${name}" PROPERTIES LABELS mpi TIMEOUT 120
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_btl_vader_single_copy_mechanism=none")
endfunction()

glint_mpi_test(same-bytes-1-rank same_bytes 1 2)
glint_mpi_test(same-bytes-2-ranks same_bytes 2 1)
glint_mpi_test(same-bytes-3-ranks same_bytes 3 2)
# The scalar renderer (--scalar) over MPI: glint-render --scalar's bytes too.
glint_mpi_test(same-bytes-2-ranks-scalar same_bytes 2 1 --scalar)
# The x86-64 renderer (--simd scalar; every CPU runs it): the same bytes.
glint_mpi_test(same-bytes-2-ranks-simd-scalar same_bytes 2 1 --simd scalar)
# Every estimator glint-render holds that the build compiled, and the choice from the scene.
foreach(estimator IN LISTS GLINT_RENDER_ESTIMATORS)
  if(estimator IN_LIST GLINT_BUILT_VARIANTS AND NOT estimator STREQUAL GLINT_DEFAULT_VARIANT)
    string(REPLACE "_" "-" dashed ${estimator})
    glint_mpi_test(same-bytes-3-ranks-${dashed} estimator_same_bytes 3 1 ${dashed})
  endif()
endforeach()
if(GLINT_BLIND_SPOT_VARIANT IN_LIST GLINT_BUILT_VARIANTS)
  glint_mpi_test(same-bytes-2-ranks-auto estimator_same_bytes 2 2 auto)
  glint_mpi_test(resume-vcm-across-programs resume_across caustic)
endif()
glint_mpi_test(resume-across-programs resume_across)
glint_mpi_test(same-bytes-2-ranks-textured textured_same_bytes 2 1)
glint_mpi_test(different-images different_images)
glint_mpi_test(scene-error scene_error)
glint_mpi_test(bad-option bad_option)
glint_mpi_test(different-settings different_settings)
glint_mpi_test(killed-rank killed_rank)
glint_mpi_test(sigusr1 stopped USR1 138)
glint_mpi_test(sigterm stopped TERM any)
set_tests_properties("mpi: killed-rank" "mpi: sigusr1" "mpi: sigterm" PROPERTIES
                     LABELS "mpi;long")
