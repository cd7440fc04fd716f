#pragma once
// What glint-render and glint-render-mpi share, so that both take the same options and keep the
// same promises: the options, their parsing and the usage text; the checks of the outputs
// before any rendering; outputs staged in temporaries that a second stop signal removes; the
// stop signals; the execution model (wavefront or scalar); loading the scene; checkpoints (their
// key, the one resumed, the one written between passes) and the time limit; and the end of a
// run: the files written together, the summary line, the warnings and the exit status.
//
// None of it depends on the variant: it is compiled once, in render_command.cpp (the glint-cli
// library), rather than in each of the renderer executables, one per variant. What the variant
// decides reaches it as data (Program); the variant's type and the renderer it picks are
// render_variant.hpp's, which only the programs' own translation units include.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "glint/image/pixel_sums.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/render/renderer.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

class LoadProgress;

/// What tells the programs apart in their messages and their usage text.
struct Program {
  const char* name;                ///< "glint-render": the prefix of every message
  std::string_view usage_line;     ///< "usage: glint-render SCENE [options]"
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
};

// --- The execution model ------------------------------------------------------------------
// A chain variant (glint::WavefrontConfig: one lobe per bounce) has two renderers with the same
// interface: WavefrontRenderer, which advances batches of paths stage by stage, and Renderer,
// one path at a time. Both call the same ChainEstimator::step and give the same image bit for
// bit; a run names the one it used, and a checkpoint belongs to one (its sums are the same, but
// the check that a resume continues the same render stays strict).
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
  std::optional<int> spp, max_depth, width, height, threads;
  std::uint64_t seed = 0;
  bool scalar = false;  ///< --scalar: Renderer, where the variant also has WavefrontRenderer
  std::optional<glint::Simd> simd;  ///< --simd, unless auto (the widest this CPU runs)
  std::optional<std::string> checkpoint, resume;
  double checkpoint_interval = 60.0;
  std::optional<double> time_limit;
  bool quiet = false;
  bool help = false;  ///< -h or --help: nothing after it was read
};

/// The run's execution model: wavefront where the variant has it, unless --scalar.
ExecutionModel execution_model(const Program& program, const Options& options);

/// A bad command line: status 2, the message and where to find the options (--help).
struct UsageError {
  std::string message;
};

// --- The instruction set ------------------------------------------------------------------
// glint-render holds its renderer compiled for x86-64, x86-64-v3 (AVX2) and x86-64-v4
// (AVX-512), and runs the widest that the CPU has, or the one --simd names. They give the same
// image bit for bit: each formula is the same IEEE operations in the same order at every width
// (-ffp-contract=off; explicit fused multiply-adds, by instruction or by the C library).

/// Whether this CPU runs code compiled for `simd` (and the operating system saves its registers).
bool cpu_runs(glint::Simd simd);

/// The instruction set of the run: --simd's, or the widest of the program's that this CPU runs.
/// Throws UsageError for one the program was not built with or the CPU lacks.
glint::Simd run_simd(const Program& program, const Options& options);

/// A program's own option: given the argument and a way to take its value, says whether it
/// was one (and took it), or throws UsageError.
using ExtraOption =
    std::function<bool(std::string_view arg, const std::function<std::string_view()>& value)>;

Options parse_options(int argc, char** argv, const Program& program, const ExtraOption& extra = {});

/// What --help prints on stdout.
std::string help_text(const Program& program);

// --- Stop signals -------------------------------------------------------------------------
// The first stop signal stops after the current pass and writes the image of the passes done;
// a second one exits at once: another signal, or the same one a second or more after the first
// (supervisors such as `timeout` send the process and its process group one copy each).

/// Set by the first stop signal: the render's RenderControl::stop.
extern std::atomic<bool> stop_requested;

/// Makes `signals` (at most 4) stop the render; `program` names the message of a second one.
void install_signal_handlers(const char* program, std::span<const int> signals);

// --- Outputs ------------------------------------------------------------------------------

/// Checks every output of the run before any rendering (throws ImageWriteError) and returns the
/// PNG's path.
std::string check_outputs(const Options& options);

// --- The scene and the settings -----------------------------------------------------------

/// The text of the scene file `file`, with its reading reported (throws SceneError).
std::string scene_file_text(LoadProgress& loading, const std::string& file);

/// The hash of a scene file's bytes that a checkpoint records: of the text that was parsed, so
/// that any edit, even one that renders the same, makes a checkpoint another scene's.
std::uint64_t scene_text_hash(std::string_view text);

/// Parses the scene's text, read from `source`, and builds it, with its loading reported. The
/// text is freed once parsed, before the build: it is as large as the scene file (76 MB for a
/// million spheres), and the build is when loading needs the most memory.
glint::Scene parse_and_build(LoadProgress& loading, std::string text, const std::string& source);

/// A scene file read, parsed and built, and the scene_text_hash of its text.
struct LoadedScene {
  glint::Scene scene;
  std::uint64_t text_hash = 0;  ///< 0 unless asked for
};

/// Loads the scene file `file`, reporting its loading on stderr if `report` (load_progress.hpp),
/// hashing its text if `hash` (for checkpoints).
LoadedScene load_scene(const std::string& file, bool report, bool hash);

/// The scene's settings with the options' overrides; throws UsageError when they do not fit
/// together (the scene's own settings were checked when it was read: what fails is an option).
glint::RenderSettings render_settings(const Options& options, const glint::Scene& scene);

// --- Checkpoints and the passes -----------------------------------------------------------

/// The checkpoints of a run: the key its checkpoints carry, the checkpoint it resumes, and, kept
/// by the pass callback, the count of the last completed pass for the checkpoint written at the
/// end (whatever stops the render after it) from the render's own sums. Between passes it writes a
/// checkpoint every
/// --checkpoint-interval seconds and applies --time-limit.
class PassKeeper {
 public:
  /// `scene_hash`: scene_text_hash of the scene file's text, needed only when a checkpoint is
  /// written or resumed. Throws CheckpointError for a checkpoint that cannot be resumed.
  PassKeeper(const Program& program, const Options& options, const glint::RenderSettings& settings,
             std::uint64_t scene_hash);
  PassKeeper(const PassKeeper&) = delete;
  PassKeeper& operator=(const PassKeeper&) = delete;

  /// Where the render begins: after the resumed checkpoint's passes, or at the start.
  glint::RenderStart start() const;

  /// The pass callback: false stops the render after this pass.
  bool pass_done(const glint::PassReport& pass);
  glint::PassCallback callback();

  bool time_is_up() const { return time_is_up_; }
  /// Writes the checkpoint of the last completed pass, whose sums are `sums` (the render's
  /// RenderResult::sums, kept with RenderControl::keep_sums), to --checkpoint's file, piece by
  /// piece. Throws ImageWriteError naming the file.
  void write_final_checkpoint(const glint::PixelSums& sums) const;

 private:
  const Program& program_;
  const Options& options_;
  glint::CheckpointKey key_;
  std::optional<glint::Checkpoint> resumed_;
  int last_passes_ = 0, last_spp_ = 0;  ///< of the last completed pass
  bool time_is_up_ = false;
  double last_checkpoint_ = 0.0;
};

// --- The end of a run ---------------------------------------------------------------------

/// How the run is reported at its end, besides the result.
struct RunReport {
  /// Who rendered, for the summary line: "2 threads", "3 ranks x 2 threads".
  std::string workers;
  /// Lines printed after the summary line (unless --quiet), each ending in a newline.
  std::string after_summary;
};

/// Writes the run's checkpoint (from `result.sums`, then freed), then its images (together or
/// none), and says how it ended: the summary line, warnings, what a stop left. Returns the exit
/// status: 1 when the checkpoint could not be written (the images were all the same). Throws
/// ImageWriteError when an image cannot be written.
int finish_run(const Program& program, const Options& options, const std::string& output,
               const glint::RenderSettings& settings, glint::RenderResult result,
               const PassKeeper& keeper, const RunReport& report);

/// A run that failed: its exit status and what to print on stderr (ending in a newline).
struct Failure {
  int status = 1;
  std::string message;
};

/// The failure of the exception being handled (call it in a catch block): 2 with the usage for
/// a bad option, 3 for a scene this variant cannot render, 1 for a bad scene (its message is
/// already "FILE:LINE: error: PROBLEM") or any other error.
Failure current_failure(const Program& program);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
