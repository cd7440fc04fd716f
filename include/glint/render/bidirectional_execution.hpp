#pragma once
// The bidirectional execution model: the passes, tiles and sample keys of a camera-path render
// (render/scalar_execution.hpp), each sample a camera subpath through its pixel and a light
// subpath joined by every strategy (render/estimators/bidirectional.hpp). The strategies that
// end at the camera's pixel add to its samples' sum; the joins of light vertices to the camera
// land as splats on the pixels that see them (the sums' splat layer, image/splat_sums.hpp), each
// pixel weighting its splat by the power heuristic for its own filter density.
//
// The camera subpath draws from the sample's own stream, the light subpath from a stream of its
// own (LightTracingExecution::kLightStream), both keyed by (pixel, sample index, seed), never by
// thread; splats add in fixed point. So the image is the same bits for any thread count, tile
// order or pass split.

#include <atomic>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "glint/config.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/bidirectional.hpp"
#include "glint/render/film_splatter.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <typename C>
class BidirectionalExecution {
  static_assert(RenderConfig<C>);

 public:
  static constexpr const char* kName = "bidirectional";
  /// Its joins to the camera land on any pixel: the sums it adds to have a splat layer.
  static constexpr bool kSplats = true;

  BidirectionalExecution(const Scene& scene, const RenderSettings& settings)
      : camera_(scene.camera(), settings.width, settings.height),
        splatter_(settings),
        tracer_(scene, camera_, settings.max_depth, float(settings.width) * float(settings.height),
                splatter_.has_area()),
        settings_(settings) {}
  BidirectionalExecution(const BidirectionalExecution&) = delete;
  BidirectionalExecution& operator=(const BidirectionalExecution&) = delete;

  /// Each thread's two subpaths, allocated once.
  struct ThreadState {
    explicit ThreadState(const BidirectionalExecution& execution)
        : camera(std::size_t(execution.tracer_.subpath_capacity())),
          light(std::size_t(execution.tracer_.subpath_capacity())) {}
    std::vector<PathVertex> camera, light;
  };

  void render_tile(ThreadState& state, const Tile& tile, int first, int last, PixelSums& sums,
                   TraceCounters& counters, std::atomic<std::uint64_t>& progress,
                   std::uint64_t& samples) const {
    SplatSums& splats = sums.splats();
    typename C::sampler camera_sampler, light_sampler;
    const auto splat = [&](Vec2 film, const Color& light, float filter_weight) {
      splatter_.add(
          splats, film, light,
          [&](float density) { return 1.0f / (1.0f + density * density * filter_weight); },
          counters);
    };
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        ColorSum sum = sums.at(x, y);
        for (int s = first; s < last; ++s) {
          const PixelSample key{std::uint32_t(x), std::uint32_t(y), std::uint32_t(s),
                                std::uint32_t(settings_.samples_per_pixel), settings_.seed};
          camera_sampler.start(key);
          PixelSample light_key = key;
          light_key.seed ^= LightTracingExecution<C>::kLightStream;
          light_sampler.start(light_key);
          Vec2 film(float(x) + 0.5f, float(y) + 0.5f);
          float filter_density = 0.0f;
          if constexpr (C::antialiasing::enabled) {
            const Vec2 offset =
                C::antialiasing::offset(camera_sampler.next_2d(), settings_.antialias_sigma);
            film += offset;
            filter_density = C::antialiasing::density(offset, settings_.antialias_sigma);
          }
          const Color sample =
              tracer_.sample(camera_.ray_through(film), filter_density, camera_sampler,
                             light_sampler, std::span<PathVertex>(state.camera),
                             std::span<PathVertex>(state.light), splat, counters);
          if (std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z))
            sum += ColorSum(sample);
          else
            ++counters.invalid_samples;
        }
        sums.at(x, y) = sum;
        samples += std::uint64_t(last - first);
      }
    progress.store(samples, std::memory_order_relaxed);
  }

 private:
  Camera camera_;
  FilmSplatter<C> splatter_;
  BidirectionalPathTracer<C> tracer_;  // holds a reference to camera_, declared before it
  RenderSettings settings_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
