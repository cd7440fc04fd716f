#pragma once
// The scene's way to glint-render-mpi's ranks: read by rank 0 and broadcast, or read by each
// (--scene-everywhere), and how long that took.

#include <cstdint>
#include <string>

#include "glint/instruction_set.hpp"
#include "mpi_measures.hpp"
#include "mpi_world.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {
class LoadProgress;
}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// How long the scene took to reach every rank, as rank 0 saw it, in seconds from the start.
struct LoadTimes {
  std::uint64_t bytes = 0;
  double read = 0.0;   ///< rank 0 had read the file
  double sent = 0.0;   ///< every rank had the text (broadcast, or each read it)
  double built = 0.0;  ///< rank 0 had parsed and built the scene
  double ready = 0.0;  ///< every rank had
};

/// The text of the scene on every rank: read by rank 0 and broadcast, or read by each
/// (`everywhere`). Throws SceneError on the ranks that cannot read it, and on the others when
/// rank 0 cannot.
std::string scene_text(const World& world, const Options& options, bool everywhere,
                       LoadProgress& loading, Clock::time_point start, LoadTimes& times);

/// --verbose's line on the scene's way to the ranks.
std::string load_line(const World& world, const LoadTimes& times, bool everywhere);

/// The CPUs this process may run on: mpirun binds each rank to a core by default.
int cpus_available();

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
