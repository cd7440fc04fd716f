// glint-render: renders a scene file with one renderer variant, chosen when this file is
// compiled: GLINT_VARIANT names a type of glint::variants (e.g. -DGLINT_VARIANT=report, or a file
// that defines it and includes this one), the default variant where it is not defined. One
// executable per variant, each linking its variant's renderers (two for a chain variant: the
// wavefront one by default, the scalar one with --scalar) from the glint-renderers library. Its
// options, outputs, signals, checkpoints, scene loading and execution model are
// render_command.hpp's, shared with glint-render-mpi and compiled once (the glint-cli library);
// this file only renders the built scene with the variant's renderer (render_variant.hpp).
//
// glint-render itself (GLINT_RENDER_SIMD_SETS, apps/CMakeLists.txt) holds this program three
// times, compiled for x86-64, x86-64-v3 (AVX2) and x86-64-v4 (AVX-512), each in glint's
// namespace for its instruction set (glint/instruction_set.hpp) and with an entry point named for
// it, glint_render_<set>. main, in the x86-64 translation unit (GLINT_RENDER_MAIN), reads the
// options, then hands the run to the entry of the instruction set chosen (--simd, or the widest
// this CPU runs), which reads them again and renders: a binary that runs on any x86-64 CPU, at
// its best width.

#include <csignal>
#include <iostream>
#include <span>
#include <string>

#include "progress_printer.hpp"
#include "render_command.hpp"
#include "render_variant.hpp"

namespace {

using glint::cli::Variant;

constexpr glint::cli::Program kProgram{
    "glint-render",
    "usage: glint-render SCENE [options]",
    "Renders SCENE (a glint scene file) with the path tracer and writes an image.",
    R"(  --threads N         worker threads (default: one per hardware thread); the image does
                      not depend on it
)",
    "",
    R"(Progress with an estimated time left goes to stderr while rendering, then one summary line.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM or SIGHUP stops after the current pass and writes the image of the
passes done, saying how many samples per pixel it holds; a second one exits at once (the
same signal again within a second is the same stop: timeout and other supervisors signal
the process and then its process group).
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written.
Exit status: 0 on success (--time-limit included), 1 for a bad scene, an unwritable output,
a checkpoint that cannot be resumed or written at the end (the images are written first)
or a CPU without an instruction set this build uses,
2 for bad options,
3 for a valid scene that this variant cannot render (a shading kind it was built without),
128 + the signal's number when a signal stopped the render (130 for SIGINT).
)",
    Variant::info.name,
    glint::cli::kVariantHasWavefront,
    glint::cli::kProgramSimds,
    glint::cli::kVariantWavefrontLanes};

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

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
  cli::Options options;
  glint::Simd simd;
  try {
    options = cli::parse_options(argc, argv, kProgram);
    simd = cli::run_simd(kProgram, options);
  } catch (const cli::UsageError&) {
    const cli::Failure failure = cli::current_failure(kProgram);
    std::cerr << failure.message;
    return failure.status;
  }
  if (options.help) {
    std::cout << cli::help_text(kProgram);
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
    std::cerr << kProgram.name << ": error: no renderer for --simd " << glint::simd_name(simd)
              << " in this program\n";
    return 1;
  }
  cli::install_signal_handlers(kProgram.name, kStopSignals);
  try {
    const std::string output = cli::check_outputs(options);
    const cli::LoadedScene loaded =
        cli::load_scene(options.scene, !options.quiet, options.checkpoint || options.resume);
    const glint::Scene& scene = loaded.scene;
    glint::check_supported<Variant>(scene);
    const glint::RenderSettings settings = cli::render_settings(options, scene);
    cli::PassKeeper keeper(kProgram, options, settings, loaded.text_hash);

    const glint::RenderControl control{cli::ProgressPrinter(!options.quiet), keeper.callback(),
                                       &cli::stop_requested, options.checkpoint.has_value()};
    glint::RenderResult result = cli::with_renderer<Variant>(
        cli::execution_model(kProgram, options), [&]<typename Renderer>() {
          return Renderer::render(scene, settings, control, keeper.start());
        });
    const std::string workers = std::to_string(result.stats.threads) + " threads";
    return cli::finish_run(kProgram, options, output, settings, std::move(result), keeper,
                           {workers, ""});
  } catch (...) {
    const cli::Failure failure = cli::current_failure(kProgram);
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
