#pragma once
// The end of a run: the checkpoint and the images written, the summary line, the warnings, what
// a stop left, and the exit status.

#include <string>

#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/renderer.hpp"
#include "pass_keeper.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// How the run is reported at its end, besides the result.
struct RunReport {
  /// Who rendered, for the summary line: "2 threads", "3 ranks x 2 threads".
  std::string workers;
  /// Lines printed after the summary line (unless --quiet), each ending in a newline.
  std::string after_summary;
  /// The processes that rendered (glint-render-mpi's ranks), for --stats-json.
  int ranks = 1;
};

/// Writes the run's checkpoint (from `result.sums`, then freed), then its images (together or
/// none), and says how it ended: the summary line, warnings, what a stop left. Returns the exit
/// status: 1 when the checkpoint could not be written (the images were all the same). Throws
/// ImageWriteError when an image cannot be written.
int finish_run(const Program& program, const Options& options, const std::string& output,
               const glint::RenderSettings& settings, glint::RenderResult result,
               const PassKeeper& keeper, const RunReport& report);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
