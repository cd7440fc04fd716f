#pragma once
// What a render is asked to do: the run-time parameters (the compile-time ones are the Config's
// policies), their check, and what a render reports back.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/scene/image_settings.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The image settings plus what only a render decides.
struct RenderSettings : ImageSettings {
  float antialias_sigma = defaults::antialias_sigma;  ///< pixels, for filters that take a width
  std::uint64_t seed = 0;
  int threads = 0;  ///< 0: one per hardware thread
  int tile_size = 16;
  /// The most samples per pixel in one pass. Passes grow from one sample, doubling the samples
  /// done, up to this: a stop request waits for the current pass, so a smaller cap answers it
  /// sooner, at the cost of a synchronisation of all threads per pass. It never changes the
  /// finished image, only which intermediate images exist.
  int max_pass_samples = 32;

  /// The settings a scene asks for (its file's `image` and `antialias` statements).
  static RenderSettings from(const Scene& scene) {
    RenderSettings settings;
    static_cast<ImageSettings&>(settings) = scene.image();
    settings.antialias_sigma = scene.antialias_sigma();
    return settings;
  }
};

/// Throws SettingsError naming the first setting outside glint's limits (the same limits and
/// messages as a scene file's `image` statement).
inline void validate(const RenderSettings& s) {
  const auto fail = [](const std::string& problem) { throw SettingsError("glint: " + problem); };
  if (std::string problem = image_settings_problem(s); !problem.empty()) fail(problem);
  if (std::string problem = antialias_sigma_problem(s.antialias_sigma); !problem.empty())
    fail(problem);
  if (s.threads < 0 || s.threads > limits::max_threads)
    fail("thread count must be between 0 and " + std::to_string(limits::max_threads));
  if (s.tile_size < 1 || s.tile_size > limits::max_tile_size)
    fail("tile size must be between 1 and " + std::to_string(limits::max_tile_size));
  if (s.max_pass_samples < 1 || s.max_pass_samples > limits::max_samples_per_pixel)
    fail("samples per pass must be between 1 and " + std::to_string(limits::max_samples_per_pixel));
}

/// The samples per pixel complete after each pass of a render of `samples_per_pixel` samples:
/// 1, 2, 4, 8, ... (each pass as many samples as all before it, so a quick first image comes
/// early and the synchronisations stay few), then steps of `max_pass_samples`, ending exactly
/// at samples_per_pixel.
inline std::vector<int> pass_ends(int samples_per_pixel, int max_pass_samples) {
  std::vector<int> ends;
  for (int done = 0; done < samples_per_pixel;) {
    const int size = std::clamp(done, 1, std::max(1, max_pass_samples));
    done = size >= samples_per_pixel - done ? samples_per_pixel : done + size;
    ends.push_back(done);
  }
  return ends;
}

/// How far a render is, passed to the progress callback on the calling thread: at least every
/// Renderer::progress_interval while rendering (even when no pixel finishes for longer) and
/// after every pass. Work is counted in samples, so the fraction moves within a pass.
struct RenderProgress {
  std::uint64_t samples_done = 0;   ///< samples rendered so far, over all pixels and passes
  std::uint64_t samples_total = 0;  ///< width x height x samples per pixel
  double elapsed_seconds = 0.0;
  int passes_done = 0;
  int pass_count = 0;
  int samples_per_pixel_done = 0;  ///< in every pixel: the image that a stop now would give
  bool last = false;               ///< the render's last call: complete, or stopped
  /// Of samples_done, those a resumed render started with (RenderControl::start): not work
  /// of this run, so not part of its speed.
  std::uint64_t samples_at_start = 0;
  double fraction() const {
    return samples_total ? double(samples_done) / double(samples_total) : 1.0;
  }
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0;  ///< samples in the image: width x height x samples per pixel done
  std::uint64_t rays = 0;     ///< camera, bounce and shadow rays
  std::uint64_t invalid_samples = 0;  ///< NaN or infinite samples, dropped (should be 0)
  /// Pixels whose mean is beyond the float range, written as the largest float (should be 0).
  std::uint64_t clamped_pixels = 0;
  int threads = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
