// stats_json.hpp's definitions.

#include "stats_json.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/detail/text.hpp"
#include "stop_signals.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

namespace {

/// A double as JSON, to 9 significant digits; 0 for what JSON cannot hold (not finite).
std::string json_number(double value) {
  if (!std::isfinite(value)) return "0";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

}  // namespace

std::string stats_json(const Program& program, const Options& options, const std::string& output,
                       const glint::RenderSettings& settings, const glint::RenderResult& result,
                       const RunEnd& end) {
  const glint::RenderStats& stats = result.stats;
  const ExecutionModel model = execution_model(program, options);
  const int lanes = model == ExecutionModel::wavefront ? program.wavefront_lanes : 1;
  const double mrays = stats.seconds > 0.0 ? double(stats.rays) / stats.seconds * 1e-6 : 0.0;
  const auto integer = [](auto value) { return std::to_string(value); };
  const std::vector<std::pair<std::string_view, std::string>> members = {
      {"program", glint::detail::json_string(program.name)},
      {"version", glint::detail::json_string(GLINT_VERSION)},
      {"variant", glint::detail::json_string(program.variant)},
      {"execution_model", glint::detail::json_string(execution_model_name(model))},
      {"simd", glint::detail::json_string(glint::simd_name(glint::kCompiledSimd))},
      {"paths_at_once", integer(lanes)},
      {"scene", glint::detail::json_string(options.scene)},
      {"output", glint::detail::json_string(output)},
      {"width", integer(settings.width)},
      {"height", integer(settings.height)},
      {"samples_per_pixel", integer(result.samples_per_pixel)},
      {"samples_per_pixel_requested", integer(settings.samples_per_pixel)},
      {"passes_done", integer(result.passes_done)},
      {"pass_count", integer(result.pass_count)},
      {"max_depth", integer(settings.max_depth)},
      {"seed", integer(settings.seed)},
      {"ranks", integer(end.ranks)},
      {"threads", integer(stats.threads)},
      {"seconds", json_number(stats.seconds)},
      {"samples", integer(stats.samples)},
      {"rays", integer(stats.rays)},
      {"mrays_per_second", json_number(mrays)},
      {"invalid_samples", integer(stats.invalid_samples)},
      {"clamped_pixels", integer(stats.clamped_pixels)},
      {"complete", result.complete() ? "true" : "false"},
      {"stopped_by",
       end.stop_signal ? glint::detail::json_string(signal_name(end.stop_signal)) : "null"},
      {"time_limit_reached", end.time_is_up ? "true" : "false"}};
  std::string json = "{\n";
  for (std::size_t i = 0; i < members.size(); ++i)
    json += "  " + glint::detail::json_string(members[i].first) + ": " + members[i].second +
            (i + 1 < members.size() ? ",\n" : "\n");
  return json + "}\n";
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
