// mpi_agreement.hpp's definitions.

#include "mpi_agreement.hpp"

#include <mpi.h>

#include <bit>
#include <cstdint>
#include <iostream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "glint/error.hpp"
#include "mpi_messages.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

int agree(const World& world, const std::optional<cli::Failure>& mine) {
  const int status = mine ? mine->status : 0;
  std::vector<int> statuses(std::size_t(world.size));
  MPI_Gather(&status, 1, MPI_INT, statuses.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int chosen[2] = {-1, 0};  // the rank whose message is printed, and the status
  if (world.rank == 0)
    for (int r = 0; r < world.size; ++r)
      if (statuses[std::size_t(r)] != 0) {
        chosen[0] = r;
        chosen[1] = statuses[std::size_t(r)];
        break;
      }
  MPI_Bcast(chosen, 2, MPI_INT, 0, MPI_COMM_WORLD);
  if (chosen[0] < 0) return 0;
  if (chosen[0] == world.rank && world.rank == 0) {
    std::cerr << mine->message;
  } else if (chosen[0] == world.rank) {
    const std::string text = failure_report(world, mine->message);
    MPI_Send(text.data(), int(text.size()), MPI_CHAR, 0, kTagFailed, MPI_COMM_WORLD);
  } else if (world.rank == 0) {
    MPI_Status probe;
    MPI_Probe(chosen[0], kTagFailed, MPI_COMM_WORLD, &probe);
    int size = 0;
    MPI_Get_count(&probe, MPI_CHAR, &size);
    std::string text(std::size_t(size), '\0');
    MPI_Recv(text.data(), size, MPI_CHAR, chosen[0], kTagFailed, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::cerr << describe_failure(world, chosen[0], text);
  }
  return chosen[1];
}

namespace {
/// Rank 0's `text`, on every rank.
std::string rank0_text(const std::string& text) {
  std::uint64_t size = text.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  std::string rank0 = text;  // rank 0's own, elsewhere overwritten
  rank0.resize(std::size_t(size));
  MPI_Bcast(rank0.data(), int(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return rank0;
}
}  // namespace

void check_same_image(const Program& program, const Options& options,
                      const glint::RenderSettings& settings, std::string_view estimator) {
  const bool scalar = execution_model(program, options) == ExecutionModel::scalar;
  const std::string renderer = std::string(program.variant) + (scalar ? ", scalar" : ", wavefront");
  const std::string rank0_renderer = rank0_text(renderer);
  const std::string rank0_estimator = rank0_text(std::string(estimator));

  struct Field {
    const char* name;
    std::uint64_t value;
  };
  const Field mine[] = {
      {"width", std::uint64_t(settings.width)},
      {"height", std::uint64_t(settings.height)},
      {"samples per pixel", std::uint64_t(settings.samples_per_pixel)},
      {"max depth", std::uint64_t(settings.max_depth)},
      {"samples per pass at most", std::uint64_t(settings.max_pass_samples)},
      {"seed", settings.seed},
      {"antialias sigma bits", std::bit_cast<std::uint32_t>(settings.antialias_sigma)}};
  constexpr std::size_t kFields = std::size(mine);
  std::uint64_t rank0[kFields];
  for (std::size_t i = 0; i < kFields; ++i)
    rank0[i] = mine[i].value;
  MPI_Bcast(rank0, int(kFields), MPI_UINT64_T, 0, MPI_COMM_WORLD);

  const std::string advice =
      ": every rank must be started with the same image options (--seed, --max-depth, --spp, "
      "--width, --height, --scalar, --estimator) and the same program";
  if (rank0_estimator != estimator)
    throw glint::Error("this rank has --estimator " + std::string(estimator) + ", rank 0 has " +
                       rank0_estimator + advice);
  if (rank0_renderer != renderer)
    throw glint::Error("this rank renders with " + renderer + ", rank 0 with " + rank0_renderer +
                       advice);
  for (std::size_t i = 0; i < kFields; ++i)
    if (rank0[i] != mine[i].value)
      throw glint::Error(std::string("this rank has ") + mine[i].name + " " +
                         std::to_string(mine[i].value) + ", rank 0 has " +
                         std::to_string(rank0[i]) + advice);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
