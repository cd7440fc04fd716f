// glint-render: renders a scene file. A variant's own program, glint-render-VARIANT, renders with
// that variant, chosen when this file is compiled (GLINT_VARIANT names a type of
// glint::variants: -DGLINT_VARIANT=report, or a file that defines it and includes this one).
// glint-render itself, compiled without it, holds the estimators of
// glint::variants::render_estimators and chooses one per run: --estimator, or from the scene
// (the path tracer, or vertex merging where the path tracer is blind to a point light's light:
// render/path_tracing_blind_spot.hpp). Each program links its variants' renderers (two for a
// chain variant: the wavefront one by default, the scalar one with --scalar) from the
// glint-renderers library. Its options, outputs, signals, checkpoints, scene loading and
// execution model are render_command.hpp's, shared with glint-render-mpi and compiled once (the
// glint-cli library); this file only renders the built scene with the chosen variant's renderer
// (render_variant.hpp).
//
// glint-render itself (GLINT_RENDER_SIMD_SETS, apps/CMakeLists.txt) holds this program three
// times, compiled for x86-64, x86-64-v3 (AVX2) and x86-64-v4 (AVX-512), each in glint's
// namespace for its instruction set (glint/instruction_set.hpp) and with an entry point named for
// it, glint_render_<set>. main, in the x86-64 translation unit (GLINT_RENDER_MAIN), reads the
// options, then hands the run to the entry of the instruction set chosen (--simd, or the widest
// this CPU runs), which reads them again and renders: a binary that runs on any x86-64 CPU, at
// its best width.

#include <csignal>
#include <cstddef>
#include <functional>
#include <iostream>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "estimator_choice.hpp"
#include "out_of_memory.hpp"
#include "progress_printer.hpp"
#include "render_command.hpp"
#include "render_variant.hpp"

namespace {

using glint::cli::Variant;

/// The name the program was built as: glint-render, or glint-render-VARIANT (defined by the file
/// apps/CMakeLists.txt generates for each variant).
#ifndef GLINT_PROGRAM_NAME
#define GLINT_PROGRAM_NAME "glint-render"
#endif

constexpr glint::cli::Program kProgram{
    GLINT_PROGRAM_NAME,
    "",
    glint::cli::kVariantDescription,
    R"(  --threads N         worker threads (default: one per hardware thread); the image does
                      not depend on it
)",
    "",
    R"(Progress with an estimated time left goes to stderr while rendering, then one summary line.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGALRM or SIGXCPU (a soft CPU-time limit, ulimit -St)
stops after the current pass and writes the image of the passes done, saying how many samples
per pixel it holds; a second one exits at once (the same signal again within a second is the
same stop: timeout and other supervisors signal the process and then its process group; so is
SIGXCPU, which the kernel repeats). A reader of stderr that goes away ends the progress only.
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written.
Exit status: 0 on success (--time-limit included), 1 for a bad scene, an unwritable output,
a checkpoint that cannot be resumed or written at the end (the images are written first)
or a CPU without an instruction set this build uses,
2 for bad options,
3 for a valid scene that this variant cannot render (a shading kind it was built without),
128 + the signal's number when a signal stopped the render (130 for SIGINT, 129 SIGHUP,
143 SIGTERM, 138 SIGUSR1, 142 SIGALRM, 152 SIGXCPU).
)",
    Variant::info.name,
    glint::cli::kVariantHasWavefront,
    glint::cli::kProgramSimds,
    glint::cli::kVariantWavefrontLanes};

// SIGUSR1, SIGALRM and SIGXCPU too: batch systems and `ulimit -t` use them to say that time is
// up, and they would otherwise kill the render with nothing written.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGALRM, SIGXCPU};

/// The program's name in its messages: the name it was built as, or the one it was run as where
/// that extends it with "-" and a name (glint-render-nightly, a copy of glint-render).
std::string program_name(const char* run_as) {
  const std::string_view built = GLINT_PROGRAM_NAME;
  std::string_view name = run_as ? run_as : "";
  if (const std::size_t slash = name.rfind('/'); slash != std::string_view::npos)
    name.remove_prefix(slash + 1);
  const bool extends = name.size() > built.size() + 1 && name.size() <= 64 &&
                       name.substr(0, built.size()) == built && name[built.size()] == '-' &&
                       name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-",
                                              built.size()) == std::string_view::npos;
  return std::string(extends ? name : built);
}

}  // namespace

#if defined(GLINT_RENDER_SIMD_SETS)
// Each defined by this file compiled for its instruction set (GLINT_ISA_LEVEL).
extern "C" int glint_render_sse2(int argc, char** argv);
extern "C" int glint_render_avx2(int argc, char** argv);
extern "C" int glint_render_avx512(int argc, char** argv);
#endif

namespace {

int run(int argc, char** argv) {
  namespace cli = glint::cli;
  const std::string name = program_name(argc > 0 ? argv[0] : nullptr);
  const std::string estimator_lines = cli::estimator_help();
  cli::Program program = kProgram;
  program.name = name.c_str();
  program.extra_options = estimator_lines;
  program.chooses_variant = glint::cli::kHoldsEstimators;
  cli::Options options;
  std::optional<std::size_t> estimator;  // an index in ProgramVariants; none: auto
  const cli::ExtraOption estimator_option = [&](std::string_view arg,
                                                const std::function<std::string_view()>& value) {
    if (estimator_lines.empty() || arg != "--estimator") return false;
    estimator = cli::parse_estimator(arg, value());
    return true;
  };
  glint::Simd simd;
  try {
    options = cli::parse_options(argc, argv, program, estimator_option);
    simd = cli::run_simd(program, options);
  } catch (const cli::UsageError&) {
    const cli::Failure failure = cli::current_failure(program);
    std::cerr << failure.message;
    return failure.status;
  }
  if (options.help) {
    std::cout << cli::help_text(program);
    return 0;
  }
  if (options.list_simd) {
    std::cout << cli::runnable_simd_list(program);
    return 0;
  }
  if (simd != glint::kCompiledSimd) {
#if defined(GLINT_RENDER_SIMD_SETS)
    switch (simd) {
      case glint::Simd::scalar:
        return glint_render_sse2(argc, argv);
      case glint::Simd::avx2:
        return glint_render_avx2(argc, argv);
      case glint::Simd::avx512:
        return glint_render_avx512(argc, argv);
    }
#endif
    std::cerr << program.name << ": error: no renderer for --simd " << glint::simd_name(simd)
              << " in this program\n";
    return 1;
  }
  cli::install_signal_handlers(program.name, kStopSignals);
  try {
    const std::string output = cli::check_outputs(options);
    const cli::LoadedScene loaded =
        cli::load_scene(options.scene, !options.quiet, options.checkpoint || options.resume);
    const glint::Scene& scene = loaded.scene;
    // Without --estimator, a resumed render continues with the variant that made it.
    std::optional<glint::Checkpoint> resumed;
    if (!estimator) resumed = cli::PassKeeper::read_resumed(options);
    const std::size_t chosen = estimator ? *estimator : cli::automatic_estimator(scene, resumed);
    return cli::with_program_variant(chosen, [&]<typename V>() {
      // What the messages, the summary, the checkpoint and the EXR header say is V's.
      program.variant = V::info.name;
      program.has_wavefront = cli::kHasWavefront<V>;
      program.wavefront_lanes = cli::kWavefrontLanes<V>;
      glint::check_supported<V>(scene);
      const glint::RenderSettings settings = cli::render_settings(options, scene);
      cli::PassKeeper keeper(program, options, settings, loaded.text_hash, std::move(resumed));

      const glint::RenderControl control{cli::ProgressPrinter(!options.quiet), keeper.callback(),
                                         &cli::stop_requested, options.checkpoint.has_value()};
      glint::RenderResult result = cli::with_memory_for(
          [&] { return cli::image_memory(settings, options.resume.has_value(), cli::kSplats<V>); },
          [&] {
            return cli::with_renderer<V>(
                cli::execution_model(program, options), [&]<typename Renderer>() {
                  return Renderer::render(scene, settings, control, keeper.start());
                });
          });
      const std::string workers = std::to_string(result.stats.threads) + " threads";
      return cli::finish_run(program, options, output, settings, std::move(result), keeper,
                             {workers, ""});
    });
  } catch (...) {
    const cli::Failure failure = cli::current_failure(program);
    std::cerr << failure.message;
    return failure.status;
  }
}

}  // namespace

#if defined(GLINT_RENDER_SIMD_SETS)
extern "C" int GLINT_ISA_CONCAT(glint_render_, GLINT_ISA_LEVEL)(int argc, char** argv) {
  return run(argc, argv);
}
#endif

#if !defined(GLINT_RENDER_SIMD_SETS) || defined(GLINT_RENDER_MAIN)
int main(int argc, char** argv) {
  return run(argc, argv);
}
#endif
