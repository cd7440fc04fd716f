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
//
// With merging (vertex connection and merging, Georgiev et al. 2012), the light subpaths of a
// sample index are traced first, for every pixel at once (a light phase, before the camera
// subpaths of that index), their vertices kept as merge candidates in a MergeGrid
// (render/merge_grid.hpp): each camera vertex then merges with the light of every light vertex
// within the merging radius, besides every join with its own pixel's light subpath (traced
// again, from the same sample values, rather than kept), all under one power heuristic. The
// radius shrinks with the sample index i as r_1 / i^(1/8) (the progressive radius of
// Knaus and Zwicker 2011 with alpha = 3/4), so the merging's bias vanishes as samples grow; r_1 is
// kMergeRadiusPixels pixels wide at the median distance of what the camera sees. Each light path
// is keyed as the bidirectional estimator keys it, and the merges of a camera vertex are added in
// the grid's fixed order, so the image is again the same bits for any threads, tiles and passes.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

#include "glint/config.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/bidirectional.hpp"
#include "glint/render/film_splatter.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/merge_grid.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Bidirectional path tracing, and with `Merging` vertex connection and merging.
template <typename C, bool Merging>
class BidirectionalExecution {
  static_assert(RenderConfig<C>);
  using Vertex = PathVertexOf<C>;

 public:
  static constexpr const char* kName = Merging ? "vertex connection and merging" : "bidirectional";
  /// Its joins to the camera land on any pixel: the sums it adds to have a splat layer.
  static constexpr bool kSplats = true;
  /// With merging, each sample index begins with its light phase (prepare_sample): the renderer
  /// renders one sample index at a time.
  static constexpr bool kLightPhase = Merging;
  /// The first merging radius in pixels, at the median distance of what the camera sees.
  static constexpr float kMergeRadiusPixels = 1.5f;

  /// `merge_radius_pixels`: the first merging radius, in pixels at the median distance of what
  /// the camera sees (merging only).
  BidirectionalExecution(const Scene& scene, const RenderSettings& settings,
                         float merge_radius_pixels = kMergeRadiusPixels)
      : camera_(scene.camera(), settings.width, settings.height),
        splatter_(settings, camera_),
        tracer_(scene, camera_, settings.max_depth, float(settings.width) * float(settings.height),
                splatter_.has_area()),
        settings_(settings),
        merge_grid_(Merging ? std::size_t(settings.width) * std::size_t(settings.height) : 0),
        first_merge_radius_(
            Merging ? first_merge_radius(scene, camera_, settings, merge_radius_pixels) : 0.0f) {}
  BidirectionalExecution(const BidirectionalExecution&) = delete;
  BidirectionalExecution& operator=(const BidirectionalExecution&) = delete;

  /// Each thread's two subpaths, allocated once.
  struct ThreadState {
    explicit ThreadState(const BidirectionalExecution& execution)
        : camera(std::size_t(execution.tracer_.subpath_capacity())),
          light(std::size_t(execution.tracer_.subpath_capacity())) {}
    std::vector<Vertex> camera, light;
  };

  /// The light phase of sample index `sample` (merging only): the light subpaths of that index for
  /// every pixel, on `threads` threads (fewer where no more can be started), and the grid of
  /// their vertices for the sample's merging radius. The rays go to `counters`.
  void prepare_sample(int sample, int threads, TraceCounters& counters) requires Merging {
    const float radius =
        first_merge_radius_ / std::sqrt(std::sqrt(std::sqrt(float(sample) + 1.0f)));
    merge_density_ = kPi * radius * radius * float(merge_grid_.path_count());
    merge_grid_.clear();
    std::atomic<std::size_t> next_chunk{0};
    std::vector<TraceCounters> thread_counters(std::size_t(std::max(threads, 1)));
    const auto work = [&](TraceCounters& mine) {
      typename C::sampler sampler;
      std::vector<Vertex> vertices(std::size_t(tracer_.subpath_capacity()));
      for (std::size_t chunk = next_chunk.fetch_add(1, std::memory_order_relaxed);
           chunk < merge_grid_.chunk_count();
           chunk = next_chunk.fetch_add(1, std::memory_order_relaxed))
        merge_grid_.fill_chunk(chunk, [&](std::size_t path, auto& candidates) {
          const std::size_t width = std::size_t(settings_.width);
          sampler.start(light_key(PixelSample{
              std::uint32_t(path % width), std::uint32_t(path / width), std::uint32_t(sample),
              std::uint32_t(settings_.samples_per_pixel), settings_.seed}));
          const std::size_t n = tracer_.light_subpath(sampler, vertices, mine);
          tracer_.merge_candidates(std::span<Vertex>(vertices).first(n), merge_density_,
                                   [&](const MergeCandidate& c) { candidates.push_back(c); });
        });
    };
    {
      std::vector<std::jthread> helpers;
      for (std::size_t t = 1; t < thread_counters.size(); ++t) {
        try {
          helpers.emplace_back(work, std::ref(thread_counters[t]));
        } catch (const std::system_error&) {
          break;  // the threads that started, and this one, take every chunk
        }
      }
      work(thread_counters[0]);
    }
    for (const TraceCounters& c : thread_counters) {
      counters.rays += c.rays;
      counters.invalid_samples += c.invalid_samples;
    }
    merge_grid_.build_grid(radius);
  }

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
          // With merging, the light phase traced this light subpath from the same values.
          light_sampler.start(light_key(key));
          Vec2 film(float(x) + 0.5f, float(y) + 0.5f);
          float filter_density = 0.0f;
          if constexpr (C::antialiasing::enabled) {
            const Vec2 offset =
                C::antialiasing::offset(camera_sampler.next_2d(), settings_.antialias_sigma);
            film += offset;
            filter_density = C::antialiasing::density(offset, settings_.antialias_sigma);
          }
          Color sample;
          if constexpr (Merging) {
            sample = merged_sample(camera_.sample_ray(film, camera_sampler), filter_density,
                                   camera_sampler, light_sampler, state, splat, counters);
          } else {
            sample = tracer_.sample(camera_.sample_ray(film, camera_sampler), filter_density,
                                    camera_sampler, light_sampler, std::span<Vertex>(state.camera),
                                    std::span<Vertex>(state.light), splat, counters);
          }
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
  /// The stream a sample's light subpath draws from.
  static PixelSample light_key(PixelSample key) {
    key.seed ^= LightTracingExecution<C>::kLightStream;
    return key;
  }

  /// A camera subpath through the pixel and its light subpath, the one the light phase traced
  /// from `light_sampler`'s values (traced again): every join of the two, and every merge of the
  /// camera vertices with the light phase's candidates.
  template <typename Splat>
  Color merged_sample(const Ray& ray, float filter_density, typename C::sampler& camera_sampler,
                      typename C::sampler& light_sampler, ThreadState& state, Splat& splat,
                      TraceCounters& counters) const {
    Color radiance(0.0f);
    const std::size_t t = tracer_.camera_subpath(ray, filter_density, camera_sampler,
                                                 std::span<Vertex>(state.camera), counters);
    const std::size_t s =
        tracer_.light_subpath(light_sampler, std::span<Vertex>(state.light), counters);
    tracer_.prepare_camera_merges(std::span<Vertex>(state.camera.data(), t), merge_density_);
    const std::span<const Vertex> z(state.camera.data(), t);
    radiance += tracer_.connect(z, std::span<const Vertex>(state.light.data(), s), camera_sampler,
                                splat, merge_density_, counters);
    for (std::size_t end = 2; end <= t; ++end) {
      const std::optional<MergeTarget<Vertex>> target =
          tracer_.merge_target(z.first(end), merge_density_);
      if (!target) continue;
      merge_grid_.for_each_near(target->vertex->point, [&](const MergeCandidate& candidate) {
        radiance += tracer_.merge(*target, candidate);
      });
    }
    return radiance;
  }

  /// `pixels` pixels at the median distance of the first hits of a grid of rays
  /// through the image; one pixel at distance one where they hit nothing.
  static float first_merge_radius(const Scene& scene, const Camera& camera,
                                  const RenderSettings& settings, float pixels) {
    constexpr int kGrid = 16;
    std::vector<float> distances;
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i) {
        const Vec2 film((float(i) + 0.5f) * float(settings.width) / float(kGrid),
                        (float(j) + 0.5f) * float(settings.height) / float(kGrid));
        const Ray ray = camera.ray_through(film);
        if (const std::optional<SphereHit> hit = scene.closest_hit(ray))
          distances.push_back(hit->t);
      }
    if (distances.empty()) return pixels * camera.pixel_size();
    const auto middle = distances.begin() + std::ptrdiff_t(distances.size() / 2);
    std::nth_element(distances.begin(), middle, distances.end());
    return pixels * camera.pixel_size() * *middle;
  }

  Camera camera_;
  FilmSplatter<C> splatter_;
  BidirectionalPathTracer<C> tracer_;  // holds a reference to camera_, declared before it
  RenderSettings settings_;
  MergeGrid<MergeCandidate> merge_grid_;  ///< the light phase's merge candidates (merging only)
  float first_merge_radius_;              ///< the merging radius of sample index 0
  float merge_density_ = 0.0f;            ///< eta of the sample index being rendered
};

/// Vertex connection and merging: the bidirectional execution with a light phase per sample
/// index and merges at every camera vertex (a class of its own, which a build can instantiate
/// explicitly).
template <typename C>
class VertexMergingExecution : public BidirectionalExecution<C, true> {
 public:
  using BidirectionalExecution<C, true>::BidirectionalExecution;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
