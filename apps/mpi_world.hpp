#pragma once
// glint-render-mpi's rank among the others, and how a rank's failure reaches rank 0 and ends
// the run.

#include <string>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// This process among the others: its rank, how many there are, its host and the program's
/// name (for messages).
struct World {
  int rank = 0;
  int size = 1;
  std::string host;
  std::string program;
};

/// Prints `message` and ends every rank (MPI_Abort), with status 1.
[[noreturn]] void abort_run(const std::string& message);

/// What a rank that failed sends rank 0: its host, a newline, and its message.
std::string failure_report(const World& world, std::string message);

/// Rank 0's words for another rank's failure_report.
std::string describe_failure(const World& world, int rank, const std::string& report);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
