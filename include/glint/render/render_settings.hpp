#pragma once
// What a render is asked to do: the run-time parameters (the compile-time ones are the Config's
// policies), their check, and what a render reports back.

#include <cstddef>
#include <cstdint>
#include <string>

#include "glint/error.hpp"
#include "glint/scene/image_settings.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

/// The image settings plus what only a render decides.
struct RenderSettings : ImageSettings {
  float antialias_sigma = defaults::antialias_sigma;  ///< pixels, for filters that take a width
  std::uint64_t seed = 0;
  int threads = 0;  ///< 0: one per hardware thread
  int tile_size = 16;

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
}

/// How far a render is, passed to the progress callback as tiles complete.
struct RenderProgress {
  std::size_t tiles_done = 0;
  std::size_t tiles_total = 0;
  double elapsed_seconds = 0.0;
  double fraction() const { return tiles_total ? double(tiles_done) / double(tiles_total) : 1.0; }
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0;
  std::uint64_t rays = 0;             ///< camera, bounce and shadow rays
  std::uint64_t invalid_samples = 0;  ///< NaN or infinite samples, dropped (should be 0)
  int threads = 0;
};

}  // namespace glint
