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
#include <cstdint>
#include <string>

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/light_tracer.hpp"
#include "glint/render/film_splatter.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/scene_lights.hpp"
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
        splatter_(settings, camera_) {
    if (!splatter_.has_area())
      throw SettingsError(
          "glint: light tracing needs a pixel filter with an area (antialias sigma > 0 with the "
          "Gaussian filter): no light path reaches a pixel's centre exactly");
    check_supported(scene);
  }

  /// Throws UnsupportedSceneError, naming the background's line, for a scene whose background
  /// is not black.
  static void check_supported(const Scene& scene) {
    if (!light_paths_carry_all_light(scene))
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
              sampler,
              [&](Vec2 film, const Color& light) {
                splatter_.add(
                    splats, film, light, [](float) { return 1.0f; }, counters);
              },
              counters);
        }
        samples += std::uint64_t(last - first);
      }
    progress.store(samples, std::memory_order_relaxed);
  }

 private:
  Camera camera_;
  LightTracer<C> tracer_;  // holds a reference to camera_, declared before it
  RenderSettings settings_;
  FilmSplatter<C> splatter_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
