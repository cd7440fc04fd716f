#pragma once
// What a run of glint-render or glint-render-mpi is: the program (what its variant decides,
// as data: Program) and the options it was given (Options), and from them the execution model
// and the names the messages, the summary line and the EXR header give the renderer.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "glint/image/tone_map.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// What tells the programs apart in their messages and their usage text.
struct Program {
  const char* name;                ///< "glint-render": the prefix of every message
  std::string_view launcher;       ///< what runs it, before its name: "", "mpirun -n N "
  std::string_view description;    ///< the paragraph after it
  std::string_view threads_help;   ///< the --threads lines of the options
  std::string_view extra_options;  ///< the program's own options, before --quiet
  std::string_view notes;          ///< what follows the options: passes, signals, exit status
  std::string_view variant;        ///< the renderer variant's name
  bool has_wavefront;              ///< the variant has the wavefront renderer (render_variant.hpp)
  /// The instruction sets the program holds a renderer for (--simd), narrowest first:
  /// glint-render all three, each compiled in its own translation units; any other program
  /// the one it was compiled for (glint::kCompiledSimd).
  std::span<const glint::Simd> simds;
  int wavefront_lanes;  ///< the paths its wavefront renderer shades at once
  /// Whether `variant` is only the default: the program chooses its variant per run
  /// (glint-render: --estimator, or from the scene).
  bool chooses_variant = false;
};

// --- The execution model ------------------------------------------------------------------
// A chain variant (glint::WavefrontConfig: one lobe per bounce) has two renderers with the same
// interface: WavefrontRenderer, which advances batches of paths stage by stage, and Renderer,
// one path at a time. Both call the same ChainEstimator::step and give the same image bit for
// bit; a run names the one it used, and a checkpoint of either continues with either.
// Every other variant has only Renderer. Which renderer a run uses is decided here only
// (execution_model; render_variant.hpp's with_renderer gives the renderer).

enum class ExecutionModel { scalar, wavefront };

struct Options {
  std::string scene;
  std::optional<std::string> output;
  std::optional<std::string> hdr;
  glint::ToneMapping tone_mapping;
  std::optional<std::string> exr;
  bool exr_half = false;
  std::optional<std::string> stats_json;  ///< --stats-json: the run's figures as JSON
  std::optional<int> spp, max_depth, width, height, threads;
  std::uint64_t seed = 0;
  bool scalar = false;  ///< --scalar: Renderer, where the variant also has WavefrontRenderer
  std::optional<glint::Simd> simd;  ///< --simd, unless auto (the widest this CPU runs)
  std::optional<std::string> checkpoint, resume;
  double checkpoint_interval = 60.0;
  std::optional<double> time_limit;
  bool quiet = false;
  bool help = false;       ///< -h or --help: nothing after it was read
  bool list_simd = false;  ///< --list-simd: nothing after it was read
};

/// The run's execution model: wavefront where the variant has it, unless --scalar.
inline ExecutionModel execution_model(const Program& program, const Options& options) {
  return program.has_wavefront && !options.scalar ? ExecutionModel::wavefront
                                                  : ExecutionModel::scalar;
}

inline std::string_view execution_model_name(ExecutionModel model) {
  return model == ExecutionModel::wavefront ? "wavefront" : "scalar";
}

/// The variant and execution model, as the summary line and the EXR header name them:
/// "fast, wavefront", "report, scalar".
inline std::string renderer_name(const Program& program, ExecutionModel model) {
  return std::string(program.variant) + ", " + std::string(execution_model_name(model));
}

/// A variant's name as its program and --estimator write it: '_' as '-' (fast_no_emitter_sampling:
/// glint-render-fast-no-emitter-sampling).
inline std::string dashed_variant_name(std::string_view variant) {
  std::string name(variant);
  for (char& c : name)
    if (c == '_') c = '-';
  return name;
}

/// What the summary line says of the code that rendered: "avx512, 16 paths at once", "avx2,
/// one path at a time".
inline std::string simd_description(const Program& program, const Options& options) {
  const bool wavefront = execution_model(program, options) == ExecutionModel::wavefront;
  const int lanes = wavefront ? program.wavefront_lanes : 1;
  return std::string(glint::simd_name(glint::kCompiledSimd)) + ", " +
         (lanes == 1 ? std::string("one path at a time")
                     : std::to_string(lanes) + " paths at once");
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
