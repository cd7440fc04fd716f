#pragma once
// The light tracing execution model: the same passes, tiles and sample keys as a camera-path
// render (render/scalar_execution.hpp), but each sample of each pixel starts one light path
// (LightTracer) instead of a camera ray, and its light lands as splats on the pixels that see it
// (the sums' splat layer, image/splat_sums.hpp). So a pass of s samples per pixel follows
// width x height x s light paths, and a pixel's value is its splats' sum over the samples per
// pixel, each splat weighted 1 / (width x height) for the light paths per sample.
//
// A light path's randomness is keyed by the (pixel, sample index, seed) that starts it, on a
// stream of its own, never by thread; splats add in fixed point, whose sums do not depend on
// their order. So the image is the same bits for any thread count, tile order or pass split.
//
//   Renderer<C, LightTracingExecution<C>>::render(scene, settings)
//
// renders the light tracing estimate (render/estimators/light_tracer.hpp: what light tracing can
// see, and what it cannot). It needs a pixel filter with an area (a splat never lands on a
// pixel's centre exactly) and a black background (light paths leave from the lights only).

#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/light_tracer.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/scene_error.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <typename C>
class LightTracingExecution {
  static_assert(RenderConfig<C>);

 public:
  static constexpr const char* kName = "light tracing";
  /// Its light lands on any pixel: the sums it adds to have a splat layer.
  static constexpr bool kSplats = true;
  /// Mixed into the seed so that light paths draw from other values than camera paths of the
  /// same pixel and sample (the estimators that follow both need them independent).
  static constexpr std::uint64_t kLightStream = 0x6c696768745f7061ull;

  /// Throws SettingsError for a pixel filter without an area and UnsupportedSceneError for a
  /// scene whose background is not black.
  LightTracingExecution(const Scene& scene, const RenderSettings& settings)
      : camera_(scene.camera(), settings.width, settings.height),
        tracer_(scene, camera_, settings.max_depth),
        settings_(settings),
        footprint_(C::antialiasing::footprint(settings.antialias_sigma)),
        per_path_(1.0f / (float(settings.width) * float(settings.height))) {
    if (!(footprint_ > 0.0f))
      throw SettingsError(
          "glint: light tracing needs a pixel filter with an area (antialias sigma > 0 with the "
          "Gaussian filter): no light path reaches a pixel's centre exactly");
    check_supported(scene);
  }

  /// Throws UnsupportedSceneError, naming the background's line, for a scene whose background
  /// is not black.
  static void check_supported(const Scene& scene) {
    if (!LightEmission::supports(scene))
      throw UnsupportedSceneError(scene.source(), scene.background_line(),
                                  "light tracing needs a black background: light paths leave "
                                  "from the point lights and emissive spheres only");
  }
  LightTracingExecution(const LightTracingExecution&) = delete;
  LightTracingExecution& operator=(const LightTracingExecution&) = delete;

  /// Nothing: a path lives on the stack.
  struct ThreadState {
    explicit ThreadState(const LightTracingExecution&) {}
  };

  void render_tile(ThreadState&, const Tile& tile, int first, int last, PixelSums& sums,
                   TraceCounters& counters, std::atomic<std::uint64_t>& progress,
                   std::uint64_t& samples) const {
    SplatSums& splats = sums.splats();
    typename C::sampler sampler;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        for (int s = first; s < last; ++s) {
          sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), std::uint32_t(s),
                                    std::uint32_t(settings_.samples_per_pixel),
                                    settings_.seed ^ kLightStream});
          tracer_.trace(
              sampler, [&](Vec2 film, const Color& light) { splat(splats, film, light, counters); },
              counters);
        }
        samples += std::uint64_t(last - first);
      }
    progress.store(samples, std::memory_order_relaxed);
  }

 private:
  /// `light` landing at film position `film`, on every pixel whose filter covers it, weighted
  /// by the filter's density there and by 1 / (width x height).
  void splat(SplatSums& splats, Vec2 film, const Color& light, TraceCounters& counters) const {
    if (!(std::isfinite(light.r) && std::isfinite(light.g) && std::isfinite(light.b))) {
      ++counters.invalid_samples;
      return;
    }
    // The pixels whose centres (x + 0.5, y + 0.5) lie within the footprint of the point.
    const float x_low = std::ceil(film.x - 0.5f - footprint_);
    const float x_high = std::floor(film.x - 0.5f + footprint_);
    const float y_low = std::ceil(film.y - 0.5f - footprint_);
    const float y_high = std::floor(film.y - 0.5f + footprint_);
    if (!(x_high >= 0.0f && y_high >= 0.0f && x_low < float(settings_.width) &&
          y_low < float(settings_.height)))
      return;
    const int x0 = int(std::fmax(x_low, 0.0f));
    const int x1 = int(std::fmin(x_high, float(settings_.width - 1)));
    const int y0 = int(std::fmax(y_low, 0.0f));
    const int y1 = int(std::fmin(y_high, float(settings_.height - 1)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 offset(film.x - (float(x) + 0.5f), film.y - (float(y) + 0.5f));
        const float density = C::antialiasing::density(offset, settings_.antialias_sigma);
        if (!(density > 0.0f)) continue;
        const Color value = light * (density * per_path_);
        if (SplatSums::representable(value))
          splats.add(x, y, value);
        else
          ++counters.invalid_samples;
      }
  }

  Camera camera_;
  LightTracer<C> tracer_;  // holds a reference to camera_, declared before it
  RenderSettings settings_;
  float footprint_;
  float per_path_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
