// mpi_rank_renderer.hpp's definitions.

#include "mpi_rank_renderer.hpp"

#include <mpi.h>

#include <algorithm>

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

std::vector<RankReport> gather_reports(const World& world, RankRenderer& renderer,
                                       std::uint64_t tiles) {
  const glint::RenderStats& stats = renderer.stats();
  const RankReport mine{renderer.queue().waited_seconds() / std::max(1, stats.threads),
                        renderer.window_seconds(),
                        stats.rays,
                        stats.invalid_samples,
                        tiles,
                        renderer.main_cpu_seconds(),
                        stats.threads};
  std::vector<RankReport> all(std::size_t(world.size));
  MPI_Gather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
  return all;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
