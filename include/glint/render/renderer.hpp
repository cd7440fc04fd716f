#pragma once
// Renderer<Config>: renders a Scene into a Film on every core.
//
// Work is split into square tiles handed out by one atomic counter; each tile's pixels are
// written by the one thread that took it, and every sample's randomness comes from hashing
// (pixel, sample index, seed). So the image is the same bit for bit whatever the thread count
// or scheduling. The hot loop has no locks, no allocation, no virtual calls and no exceptions.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "glint/config.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/film.hpp"
#include "glint/render/path_tracer.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

struct RenderSettings {
  int width = 800;
  int height = 800;
  int samples_per_pixel = 1000;
  int max_depth = 12;
  float antialias_sigma = 0.5f;  ///< pixels; used by antialiasing policies that take a width
  std::uint64_t seed = 0;
  int threads = 0;  ///< 0: one per hardware thread
  int tile_size = 16;

  /// The settings a scene file asks for.
  static RenderSettings from(const SceneDescription& scene) {
    RenderSettings settings;
    settings.width = scene.image.width;
    settings.height = scene.image.height;
    settings.samples_per_pixel = scene.image.samples_per_pixel;
    settings.max_depth = scene.image.max_depth;
    settings.antialias_sigma = scene.antialias_sigma;
    return settings;
  }
};

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

struct RenderResult {
  Film film;
  RenderStats stats;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

/// Throws SceneError if the scene uses a shading kind that Config's shading policy lacks.
template <RenderConfig C>
void check_supported(const Scene& scene) {
  const SceneDescription& description = scene.description();
  for (const SphereDescription& sphere : description.spheres) {
    if (!C::shading::supports(sphere.shading))
      throw SceneError(description.source, sphere.line,
                       "shading '" + std::string(to_string(sphere.shading)) +
                           "' is not supported by this renderer variant");
  }
}

inline void check_settings(const RenderSettings& s) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("glint: " + what); };
  if (s.width < 1 || s.width > kMaxImageSide || s.height < 1 || s.height > kMaxImageSide)
    fail("image size must be between 1 and " + std::to_string(kMaxImageSide) + " pixels a side");
  if (std::int64_t{s.width} * s.height > kMaxImagePixels)
    fail("image size exceeds " + std::to_string(kMaxImagePixels) + " pixels");
  if (s.samples_per_pixel < 1 || s.samples_per_pixel > kMaxSamplesPerPixel)
    fail("samples per pixel must be between 1 and " + std::to_string(kMaxSamplesPerPixel));
  if (s.max_depth < 0 || s.max_depth > kMaxDepth)
    fail("max depth must be between 0 and " + std::to_string(kMaxDepth));
  if (s.threads < 0 || s.threads > 4096) fail("thread count must be between 0 and 4096");
  if (s.tile_size < 1 || s.tile_size > 1024) fail("tile size must be between 1 and 1024");
  if (!(s.antialias_sigma >= 0.0f && s.antialias_sigma <= 100.0f))
    fail("antialias sigma must be in [0, 100] pixels");
}

template <RenderConfig C>
class Renderer {
 public:
  /// Renders with the given settings; `progress`, if set, is called from the calling thread
  /// as tiles complete (never from a worker).
  static RenderResult render(const Scene& scene, const RenderSettings& settings,
                             const ProgressCallback& progress = {}) {
    check_settings(settings);
    check_supported<C>(scene);
    const auto start = std::chrono::steady_clock::now();

    RenderResult result{Film(settings.width, settings.height), {}};
    const Camera camera(scene.description().camera, settings.width, settings.height);
    const PathTracer<C> tracer(scene, settings.max_depth);

    const int tiles_x = (settings.width + settings.tile_size - 1) / settings.tile_size;
    const int tiles_y = (settings.height + settings.tile_size - 1) / settings.tile_size;
    const std::size_t tile_count = std::size_t(tiles_x) * std::size_t(tiles_y);
    const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    const int thread_count = static_cast<int>(
        std::min<std::size_t>(settings.threads > 0 ? settings.threads : hardware, tile_count));

    std::atomic<std::size_t> next_tile{0};
    std::atomic<std::size_t> tiles_done{0};
    std::vector<WorkerTotals> totals(static_cast<std::size_t>(thread_count));
    {
      std::vector<std::jthread> workers;
      workers.reserve(std::size_t(thread_count));
      for (int t = 0; t < thread_count; ++t) {
        workers.emplace_back([&, t] {
          WorkerTotals& mine = totals[std::size_t(t)];
          for (std::size_t tile = next_tile++; tile < tile_count; tile = next_tile++) {
            const int x0 = int(tile % std::size_t(tiles_x)) * settings.tile_size;
            const int y0 = int(tile / std::size_t(tiles_x)) * settings.tile_size;
            render_tile(tracer, camera, settings, x0, y0, result.film, mine);
            tiles_done.fetch_add(1, std::memory_order_release);
            tiles_done.notify_all();
          }
        });
      }
      report_progress(tiles_done, tile_count, start, progress);
    }  // jthreads join here

    for (const WorkerTotals& w : totals) {
      result.stats.rays += w.counters.rays;
      result.stats.invalid_samples += w.invalid_samples;
    }
    result.stats.samples = std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                           std::uint64_t(settings.samples_per_pixel);
    result.stats.threads = thread_count;
    result.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

  /// One pixel's estimate: the mean of its samples. Exposed for tests and benchmarks.
  static Color render_pixel(const PathTracer<C>& tracer, const Camera& camera,
                            const RenderSettings& settings, int x, int y, TraceCounters& counters,
                            std::uint64_t& invalid_samples) {
    typename C::sampler sampler;
    Color sum(0.0f);
    for (int s = 0; s < settings.samples_per_pixel; ++s) {
      sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), std::uint32_t(s),
                                std::uint32_t(settings.samples_per_pixel), settings.seed});
      Vec2 film(float(x) + 0.5f, float(y) + 0.5f);
      if constexpr (C::antialiasing::enabled)
        film += C::antialiasing::offset(sampler.next_2d(), settings.antialias_sigma);
      const Color sample = tracer.radiance(camera.ray_through(film), sampler, counters);
      if (std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z))
        sum += sample;
      else
        ++invalid_samples;
    }
    return sum / float(settings.samples_per_pixel);
  }

 private:
  // Padded to a cache line so that threads never write to the same line.
  struct alignas(64) WorkerTotals {
    TraceCounters counters;
    std::uint64_t invalid_samples = 0;
  };

  static void render_tile(const PathTracer<C>& tracer, const Camera& camera,
                          const RenderSettings& settings, int x0, int y0, Film& film,
                          WorkerTotals& totals) {
    const int x1 = std::min(x0 + settings.tile_size, settings.width);
    const int y1 = std::min(y0 + settings.tile_size, settings.height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        film.at(x, y) =
            render_pixel(tracer, camera, settings, x, y, totals.counters, totals.invalid_samples);
  }

  static void report_progress(std::atomic<std::size_t>& tiles_done, std::size_t tile_count,
                              std::chrono::steady_clock::time_point start,
                              const ProgressCallback& progress) {
    std::size_t seen = 0;
    while (seen < tile_count) {
      tiles_done.wait(seen, std::memory_order_acquire);
      seen = tiles_done.load(std::memory_order_acquire);
      if (progress) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        progress(RenderProgress{seen, tile_count, elapsed});
      }
    }
  }
};

}  // namespace glint
