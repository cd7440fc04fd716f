// mpi_scene.hpp's definitions.

#include "mpi_scene.hpp"

#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <thread>

#include "glint/scene/scene_error.hpp"
#include "load_progress.hpp"
#include "scene_loading.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

std::string scene_text(const World& world, const Options& options, bool everywhere,
                       LoadProgress& loading, Clock::time_point start, LoadTimes& times) {
  if (everywhere) {
    std::string text = scene_file_text(loading, options.scene);
    times.read = seconds_since(start);
    return text;
  }
  std::string text;
  std::uint64_t size = UINT64_MAX;  // rank 0 could not read it
  std::exception_ptr failure;
  if (world.rank == 0) try {
      text = scene_file_text(loading, options.scene);
      size = text.size();
      times.read = seconds_since(start);
    } catch (...) {
      failure = std::current_exception();
    }
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (failure) std::rethrow_exception(failure);
  if (size == UINT64_MAX)
    throw glint::SceneError(options.scene, 0, "rank 0 could not read the scene");
  text.resize(std::size_t(size));
  // At most kMaxSceneFileSize (1 GiB): one count of bytes.
  MPI_Bcast(text.data(), int(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

std::string load_line(const World& world, const LoadTimes& t, bool everywhere) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%s: scene: %s, read by rank 0 after %.3f s, on every rank (%s) after %.3f s; "
                "parsed and built by rank 0 after %.3f s, by every rank after %.3f s\n",
                world.program.c_str(), megabytes(t.bytes).c_str(), t.read,
                everywhere ? "each read it" : "broadcast", t.sent, t.built, t.ready);
  return line;
}

int cpus_available() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, int(std::thread::hardware_concurrency()));
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
