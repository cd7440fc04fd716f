// finish_run.hpp's definitions.

#include "finish_run.hpp"

#include <cstdio>
#include <limits>
#include <utility>
#include <vector>

#include "glint/error.hpp"
#include "glint/io/image_writer.hpp"
#include "out_of_memory.hpp"
#include "staged_outputs.hpp"
#include "stats_json.hpp"
#include "stop_signals.hpp"

// GLINT_HAVE_EXR: the library links glint::exr (apps/CMakeLists.txt, when OpenEXR is found).
#ifdef GLINT_HAVE_EXR
#include "glint/exr/exr_image.hpp"
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

#ifdef GLINT_HAVE_EXR
namespace {

/// The render, in the EXR header: a typed attribute per setting ("glint/..."; the seed as its
/// decimal string, EXR having no 64-bit integers), and a line in the standard "comments"
/// attribute that any EXR viewer shows. The scene is named as it was given.
std::vector<glint::ExrAttribute> exr_attributes(const Program& program, const Options& options,
                                                const glint::RenderSettings& settings,
                                                const glint::RenderResult& result) {
  const std::string seed = std::to_string(settings.seed);
  const ExecutionModel model = execution_model(program, options);
  const std::string comments =
      std::string(program.name) + " " GLINT_VERSION " (" + renderer_name(program, model) +
      "): " + options.scene + ", " + std::to_string(result.samples_per_pixel) + " of " +
      std::to_string(settings.samples_per_pixel) + " samples per pixel, max depth " +
      std::to_string(settings.max_depth) + ", seed " + seed;
  return {{"comments", comments},
          {"glint/version", std::string(GLINT_VERSION)},
          {"glint/variant", std::string(program.variant)},
          {"glint/executionModel", std::string(execution_model_name(model))},
          {"glint/simd", std::string(glint::simd_name(glint::kCompiledSimd))},
          {"glint/scene", options.scene},
          {"glint/width", settings.width},
          {"glint/height", settings.height},
          {"glint/samplesPerPixel", result.samples_per_pixel},
          {"glint/samplesPerPixelRequested", settings.samples_per_pixel},
          {"glint/maxDepth", settings.max_depth},
          {"glint/antialiasSigma", settings.antialias_sigma},
          {"glint/seed", seed},
          {"glint/threads", result.stats.threads},
          {"glint/renderSeconds", result.stats.seconds}};
}

}  // namespace
#endif

int finish_run(const Program& program, const Options& options, const std::string& output,
               const glint::RenderSettings& settings, glint::RenderResult result,
               const PassKeeper& keeper, const RunReport& report) {
  const char* name = program.name;
  const int signal = received_stop_signal();
  if (result.samples_per_pixel == 0) {
    std::fprintf(stderr, "%s: stopped by %s before a pass completed: nothing written\n", name,
                 signal_name(signal));
    return 128 + signal;
  }
  // The checkpoint first, so that its sums (24 bytes a pixel) are freed before the images are
  // encoded. It is a means to the images, which are written whatever becomes of it: its
  // failure is reported last, and makes the status 1.
  std::string checkpoint_failure;
  if (options.checkpoint) {
    try {
      keeper.write_final_checkpoint(result.sums);
    } catch (const glint::ImageWriteError& error) {
      checkpoint_failure = error.what();
    }
    result.sums = glint::PixelSums();
  }

  const auto encoding = [&] {
    return "encoding the images of " + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + " pixels";
  };
  std::vector<glint::FileContents> files{{output, with_memory_for(encoding, [&] {
                                            return glint::encode_png(result.film,
                                                                     options.tone_mapping);
                                          })}};
  if (options.hdr)
    files.push_back(
        {*options.hdr, with_memory_for(encoding, [&] { return glint::encode_pfm(result.film); })});
#ifdef GLINT_HAVE_EXR
  std::size_t clamped_halves = 0;
  if (options.exr) {
    glint::ExrEncoded exr = glint::encode_exr(
        result.film,
        {options.exr_half ? glint::ExrPixelType::float16 : glint::ExrPixelType::float32,
         exr_attributes(program, options, settings, result)});
    clamped_halves = exr.clamped_values;
    files.push_back({*options.exr, std::move(exr.bytes)});
  }
#endif
  if (options.stats_json) {
    const std::string json = stats_json(program, options, output, settings, result,
                                        {report.ranks, signal, keeper.time_is_up()});
    files.push_back({*options.stats_json, std::vector<char>(json.begin(), json.end())});
  }
  std::vector<StagedOutput> images;
  for (const glint::FileContents& file : files)
    images.push_back({file.path, [&file](glint::StagedFile& staged) { staged.write(file.bytes); }});
  write_staged(images);

  if (!options.quiet) {
    const glint::RenderStats& stats = result.stats;
    std::fprintf(stderr,
                 "%s (%s): %s -> %s: %dx%d, %d spp, depth %d in %.2f s on %s: "
                 "%.3g samples, %.1f Mrays/s\n",
                 name,
                 (renderer_name(program, execution_model(program, options)) + ", " +
                  simd_description(program, options))
                     .c_str(),
                 options.scene.c_str(), output.c_str(), settings.width, settings.height,
                 result.samples_per_pixel, settings.max_depth, stats.seconds,
                 report.workers.c_str(), double(stats.samples),
                 double(stats.rays) / stats.seconds * 1e-6);
    std::fputs(report.after_summary.c_str(), stderr);
  }
  if (result.stats.invalid_samples > 0)
    std::fprintf(stderr, "%s: warning: %llu samples were NaN or infinite and dropped\n", name,
                 static_cast<unsigned long long>(result.stats.invalid_samples));
  if (result.stats.clamped_pixels > 0)
    std::fprintf(stderr,
                 "%s: warning: %llu pixels have a mean beyond the float range and were "
                 "written as the largest float (%g)\n",
                 name, static_cast<unsigned long long>(result.stats.clamped_pixels),
                 double(std::numeric_limits<float>::max()));
#ifdef GLINT_HAVE_EXR
  if (clamped_halves > 0)
    std::fprintf(stderr,
                 "%s: warning: %zu channel values beyond the largest half were "
                 "written to %s as %g\n",
                 name, clamped_halves, options.exr->c_str(), double(glint::kExrLargestHalf));
#endif
  if (options.checkpoint && !result.complete() && checkpoint_failure.empty())
    std::fprintf(stderr, "%s: %s holds the render so far: continue it with --resume %s\n", name,
                 options.checkpoint->c_str(), options.checkpoint->c_str());
  if (signal != 0)
    std::fprintf(stderr,
                 "%s: stopped by %s: %s holds %d of %d samples per pixel (%d of %d "
                 "passes)\n",
                 name, signal_name(signal), output.c_str(), result.samples_per_pixel,
                 settings.samples_per_pixel, result.passes_done, result.pass_count);
  else if (keeper.time_is_up())
    std::fprintf(stderr,
                 "%s: time limit of %g s reached: %s holds %d of %d samples per pixel "
                 "(%d of %d passes)\n",
                 name, *options.time_limit, output.c_str(), result.samples_per_pixel,
                 settings.samples_per_pixel, result.passes_done, result.pass_count);
  if (!checkpoint_failure.empty()) {
    std::fprintf(stderr, "%s: error: no checkpoint: %s (the images were written)\n", name,
                 checkpoint_failure.c_str());
    return 1;
  }
  return signal != 0 ? 128 + signal : 0;
}
}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
