#pragma once
// --stats-json: the run's figures as JSON, for scripts (bench/run-all), written with the images
// (staged_outputs.hpp): what the summary line says, as numbers and names rather than words.

#include <string>

#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/renderer.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// What the JSON says of how the run ended and who rendered it, besides the result.
struct RunEnd {
  int ranks = 1;            ///< glint-render-mpi's processes; 1 for glint-render
  int stop_signal = 0;      ///< the signal that stopped the render, or 0
  bool time_is_up = false;  ///< --time-limit stopped it
};

/// The JSON document (one member to a line, ending in a newline); its members are listed in
/// docs/glint-render.md.
std::string stats_json(const Program& program, const Options& options, const std::string& output,
                       const glint::RenderSettings& settings, const glint::RenderResult& result,
                       const RunEnd& end);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
