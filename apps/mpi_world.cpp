// mpi_world.hpp's definitions.

#include "mpi_world.hpp"

#include <mpi.h>

#include <cstdlib>
#include <iostream>

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

void abort_run(const std::string& message) {
  std::cerr << message << std::flush;
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);  // MPI_Abort does not return
}

std::string failure_report(const World& world, std::string message) {
  if (message.empty() || message.back() != '\n') message += '\n';
  return world.host + "\n" + message;
}

std::string describe_failure(const World& world, int rank, const std::string& report) {
  const std::size_t line = report.find('\n');
  return world.program + ": rank " + std::to_string(rank) + " (on " + report.substr(0, line) +
         ") failed:\n" + report.substr(line + 1);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
