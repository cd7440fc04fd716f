#pragma once
// How glint-render and glint-render-mpi choose the variant that renders a run, where the program
// holds several (render_variant.hpp's ProgramVariants): --estimator NAME, else the variant that
// made the checkpoint --resume continues, else from the scene (the path tracer, or the blind-spot
// variant where a point light shines through glass or by way of a mirror:
// render/path_tracing_blind_spot.hpp). Both programs choose alike, so that they render the same
// image with the same options. Included once per program, as render_variant.hpp is.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command_line.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/render/path_tracing_blind_spot.hpp"
#include "glint/scene/scene.hpp"
#include "pass_keeper.hpp"
#include "render_variant.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// "a, b or c".
inline std::string listed(const std::vector<std::string>& words) {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i)
    text.append(i == 0 ? "" : i + 1 == words.size() ? " or " : ", ").append(words[i]);
  return text;
}

/// --estimator's lines of the help, where the program holds the estimators (it takes
/// --estimator even where the build compiled no estimator but the default: scripts name it
/// either way); "" for a variant's own program.
inline std::string estimator_help() {
  if (!kHoldsEstimators) return "";
  const std::vector<std::string>& names = estimator_names();
  const std::string automatic =
      kBlindSpotIndex ? names.front() + " (the path tracer), or " + names[*kBlindSpotIndex] +
                            " where a point light shines through glass or by way of a "
                            "mirror: light no path from the camera can follow"
                      : names.front();
  const std::string text = "what renders the image: auto (the default: " + automatic + "), " +
                           listed(names) +
                           "; each renders the image its own program glint-render-NAME renders, "
                           "bit for bit";
  // Wrapped as the other options' lines are: from column 23 to column 92.
  constexpr std::size_t kIndent = 22, kWidth = 92;
  std::string lines = "  --estimator NAME    ";
  std::size_t column = kIndent;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::size_t length = end - start;
    if (column > kIndent && column + 1 + length > kWidth) {
      lines.append("\n").append(kIndent, ' ');
      column = kIndent;
    } else if (column > kIndent) {
      lines.push_back(' ');
      ++column;
    }
    lines.append(text, start, length);
    column += length;
    start = end + 1;
  }
  return lines + "\n";
}

/// --estimator's value: an index in ProgramVariants, or nullopt for auto. Throws UsageError.
inline std::optional<std::size_t> parse_estimator(std::string_view option, std::string_view text) {
  if (text == "auto") return std::nullopt;
  const std::vector<std::string>& names = estimator_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (text == names[i]) return i;
  std::vector<std::string> accepted{"auto"};
  accepted.insert(accepted.end(), names.begin(), names.end());
  throw UsageError{std::string(option) + " expects " + listed(accepted) + ", got '" +
                   std::string(text) + "'"};
}

/// The variant that renders `scene` where --estimator did not choose: the one that made the
/// checkpoint `resumed` continues, where the program holds it; else the default variant, or the
/// blind-spot variant where the scene has light the path tracer cannot see. The summary line
/// names the one chosen.
inline std::size_t automatic_estimator(const glint::Scene& scene,
                                       const std::optional<glint::Checkpoint>& resumed) {
  if (resumed) {
    const std::string name = dashed_variant_name(PassKeeper::made_by(*resumed));
    const std::vector<std::string>& names = estimator_names();
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return i;
  }
  if (!kBlindSpotIndex || !glint::path_tracing_blind_spot(scene)) return 0;
  return *kBlindSpotIndex;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
