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
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "glint/config.hpp"
#include "glint/image/film.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/path_tracer.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

struct RenderResult {
  Film film;
  RenderStats stats;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

/// The first sphere whose shading kind variant C's SphereShading policy does not support.
template <RenderConfig C>
std::optional<std::uint32_t> first_unsupported_sphere(const Scene& scene) {
  for (std::uint32_t i = 0; i < scene.sphere_count(); ++i)
    if (!C::sphere_shading::supports(scene.surface(i).shading)) return i;
  return std::nullopt;
}

/// Whether variant C can render the scene.
template <RenderConfig C>
bool is_supported(const Scene& scene) {
  return !first_unsupported_sphere<C>(scene).has_value();
}

/// Throws UnsupportedSceneError, naming the sphere's line, if variant C cannot render the scene.
template <RenderConfig C>
void check_supported(const Scene& scene) {
  if (const std::optional<std::uint32_t> sphere = first_unsupported_sphere<C>(scene))
    throw UnsupportedSceneError(scene.source(), scene.sphere_line(*sphere),
                                "shading '" +
                                    std::string(to_string(scene.surface(*sphere).shading)) +
                                    "' is not supported by this renderer variant");
}

template <RenderConfig C>
class Renderer {
 public:
  /// Renders with the given settings; `progress`, if set, is called from the calling thread
  /// as tiles complete (never from a worker). Throws SettingsError for settings outside the
  /// limits and UnsupportedSceneError for a scene this variant cannot render.
  static RenderResult render(const Scene& scene, const RenderSettings& settings,
                             const ProgressCallback& progress = {}) {
    validate(settings);
    check_supported<C>(scene);
    const auto start = std::chrono::steady_clock::now();

    RenderResult result{Film(settings.width, settings.height), {}};
    const Camera camera(scene.camera(), settings.width, settings.height);
    const PathTracer<C> tracer(scene, settings.max_depth);

    const TileGrid grid(settings);
    const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    const int thread_count = static_cast<int>(
        std::min<std::size_t>(settings.threads > 0 ? settings.threads : hardware, grid.count));

    std::atomic<std::size_t> next_tile{0};
    std::atomic<std::size_t> tiles_done{0};
    std::vector<PaddedCounters> counters(static_cast<std::size_t>(thread_count));
    {
      std::vector<std::jthread> workers;
      workers.reserve(std::size_t(thread_count));
      for (int t = 0; t < thread_count; ++t) {
        workers.emplace_back([&, t] {
          TraceCounters& mine = counters[std::size_t(t)].counters;
          for (std::size_t tile = next_tile++; tile < grid.count; tile = next_tile++) {
            render_tile(tracer, camera, settings, grid.tile(tile), result.film, mine);
            tiles_done.fetch_add(1, std::memory_order_release);
            tiles_done.notify_all();
          }
        });
      }
      report_progress(tiles_done, grid.count, start, progress);
    }  // jthreads join here

    for (const PaddedCounters& c : counters) {
      result.stats.rays += c.counters.rays;
      result.stats.invalid_samples += c.counters.invalid_samples;
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
                            const RenderSettings& settings, int x, int y, TraceCounters& counters) {
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
        ++counters.invalid_samples;
    }
    return sum / float(settings.samples_per_pixel);
  }

 private:
  /// Pixels [x0, x1) x [y0, y1).
  struct Tile {
    int x0, y0, x1, y1;
  };

  /// The image cut into square tiles, numbered row by row.
  struct TileGrid {
    explicit TileGrid(const RenderSettings& settings)
        : size(settings.tile_size),
          width(settings.width),
          height(settings.height),
          columns((width + size - 1) / size),
          count(std::size_t(columns) * std::size_t((height + size - 1) / size)) {}
    Tile tile(std::size_t index) const {
      const int x0 = int(index % std::size_t(columns)) * size;
      const int y0 = int(index / std::size_t(columns)) * size;
      return {x0, y0, std::min(x0 + size, width), std::min(y0 + size, height)};
    }
    int size, width, height, columns;
    std::size_t count;
  };

  // Padded to a cache line so that threads never write to the same line.
  struct alignas(64) PaddedCounters {
    TraceCounters counters;
  };

  static void render_tile(const PathTracer<C>& tracer, const Camera& camera,
                          const RenderSettings& settings, const Tile& tile, Film& film,
                          TraceCounters& counters) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        film.at(x, y) = render_pixel(tracer, camera, settings, x, y, counters);
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
