#pragma once
// WavefrontExecution<Config>: the execution model that advances many paths together. Each
// thread keeps a batch of paths in flight, in structure-of-arrays form (ThreadState), and runs
// every stage over the whole batch before the next: trace the rays to their closest hits eight
// at a time, shade every hit (emission, the light rays to queue, the next direction, roulette),
// trace the queued shadow and emitter rays eight at a time, add what they found, retire the
// finished paths and refill the batch with the next samples of the tile. This is the shape of
// pbrt-v4's wavefront/ integrator and Mitsuba 3's wavefront mode, on a CPU thread's scale.
//
// Each path's arithmetic is ChainEstimator's (render/estimators/chain.hpp): the same
// PathContext and ReportMaterial, the same draws from the same sampler in the same order, and
// batched queries that answer exactly what the single-ray ones do. Only where light found by a
// shadow or emitter ray is added differs (after the batch's rays are traced instead of at once),
// which can move a sample's last bits. A path's arithmetic never depends on the other paths of
// its batch, on its place in the batch or on the thread, and a pixel's samples are added to its
// sum in index order: the image is the same bit for bit whatever the thread count.

#include <atomic>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "glint/config.hpp"
#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/scattering.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"

// Everything the shading and camera stages call is inlined into them. Besides speed, this
// keeps the scalar renderer's code what it is alone: the sampler's draws, the lobe sampling
// and the emitter sampling would otherwise have two callers in a program that holds both
// renderers, GCC would leave them out of line, and the multiply-adds it fuses across those
// calls would change the last bits of the scalar renderer's images.
#if defined(__GNUC__) && !defined(__clang__)
#define GLINT_FLATTEN [[gnu::flatten]]
#else
#define GLINT_FLATTEN
#endif

// Each stage that runs once per batch stays a function of its own: a call per 256 paths costs
// nothing, and a profile (perf report) then gives every stage's share of the time by name.
#define GLINT_STAGE [[gnu::noinline]]

namespace glint {

/// Whether variant C can be rendered by WavefrontRenderer: it follows one lobe per bounce, so a
/// sample is one path. (The report's tree model follows every lobe: a sample is a tree of rays.)
template <typename C>
concept WavefrontConfig =
    RenderConfig<C> && std::same_as<typename C::material_model, StochasticMaterialModel>;

template <RenderConfig C>
class WavefrontExecution {
  static_assert(WavefrontConfig<C>,
                "WavefrontRenderer renders chain configurations only (material_model = "
                "StochasticMaterialModel, one lobe per bounce); the report's tree model follows "
                "every lobe at each hit, so use Renderer<C> for it");

 public:
  static constexpr const char* kName = "wavefront";
  using SamplerType = typename C::sampler;
  using Context = PathContext<C>;
  using Origin = typename Context::Origin;
  static constexpr bool kSamplesEmitters = Context::kSamplesEmitters;

  /// Paths in flight per thread: enough that eight-ray batches stay full while paths end at
  /// different depths, few enough that the batch's state stays in the core's L2 cache.
  static constexpr int kPaths = 256;
  /// Samples that may be started beyond the first one not yet added to its pixel: a long path
  /// holds back the sums behind it, not the paths that start after it.
  static constexpr int kWindow = 4 * kPaths;
  /// Shadow rays queued before they are traced (more are traced in several rounds).
  static constexpr int kShadowQueue = 2 * kPaths;

  WavefrontExecution(const Scene& scene, const RenderSettings& settings)
      : scene_(scene),
        context_(scene, settings.max_depth),
        camera_(scene.camera(), settings.width, settings.height),
        settings_(settings) {}

  /// A thread's batch of paths and its queues, allocated once per render.
  class ThreadState {
   public:
    explicit ThreadState(const WavefrontExecution&)
        : rays(kPaths / RayBatch::kWidth),
          hits(kPaths / RayBatch::kWidth),
          throughput(kPaths),
          radiance(kPaths),
          depth(kPaths),
          sample(kPaths),
          from(kPaths),
          sampler(kPaths),
          shading_throughput(kPaths),
          albedo(kPaths),
          irradiance(kPaths),
          emitter_light(kPaths),
          pending(kPaths),
          ends(kPaths),
          shadow_rays(kShadowQueue / RayBatch::kWidth),
          shadow_owner(kShadowQueue),
          shadow_irradiance(kShadowQueue),
          emitter_rays(kPaths / RayBatch::kWidth),
          emitter_owner(kPaths),
          emitter_sphere(kPaths),
          results(kWindow),
          result_ready(kWindow) {}

   private:
    friend class WavefrontExecution;

    // The paths in flight, 0 .. live-1. Rays and hits in blocks of eight for the batched
    // queries; path p is lane p % 8 of block p / 8.
    detail::AlignedArray<RayBatch> rays;
    detail::AlignedArray<HitBatch> hits;
    std::vector<Color> throughput;
    std::vector<Color> radiance;
    std::vector<int> depth;
    std::vector<std::uint64_t> sample;  ///< the path's sample, numbered within the tile's work
    std::vector<Origin> from;
    std::vector<SamplerType> sampler;

    // What the current bounce waits for: light that the queued rays may bring, added once they
    // are traced, in ChainEstimator's order (point lights, then the emitter sample).
    std::vector<Color> shading_throughput;  ///< the throughput at the hit
    std::vector<Color> albedo;
    std::vector<Color> irradiance;
    std::vector<Color> emitter_light;
    std::vector<std::uint8_t> pending;  ///< kDirectLight | kEmitterRay | kEmitterVisible
    std::vector<std::uint8_t> ends;     ///< the path ends after this bounce

    detail::AlignedArray<RayBatch> shadow_rays;
    std::vector<std::uint32_t> shadow_owner;
    std::vector<Color> shadow_irradiance;
    int shadow_count = 0;

    detail::AlignedArray<RayBatch> emitter_rays;
    std::vector<std::uint32_t> emitter_owner;
    std::vector<std::uint32_t> emitter_sphere;
    int emitter_count = 0;

    // Finished samples waiting to be added to their pixel in order, at sample % kWindow.
    std::vector<Color> results;
    std::vector<std::uint8_t> result_ready;
  };

  void render_tile(ThreadState& state, const Tile& tile, int first, int last, PixelSums& sums,
                   TraceCounters& counters, std::atomic<std::uint64_t>& progress,
                   std::uint64_t& samples) const {
    // In 64 bits: a tile of 1024x1024 pixels times a pass of up to 2^20 samples is 2^40.
    const auto per_pixel = std::uint64_t(last - first);
    const auto total = std::uint64_t(tile.pixel_count()) * per_pixel;
    const PieceLayout piece{tile, first, per_pixel};
    std::uint64_t started = 0;
    std::uint64_t summed = 0;
    int live = 0;
    for (;;) {
      while (live < kPaths && started < total && started - summed < std::uint64_t(kWindow))
        start_path(state, live++, started++, piece);
      if (live == 0) break;
      trace_closest_hits(state, live, counters);
      for (int p = 0; p < live; ++p)
        shade(state, p, counters);
      trace_shadow_rays(state);
      trace_emitter_rays(state);
      live = gather_and_retire(state, live);
      summed = add_finished(state, piece, summed, started, sums, counters);
    }
    samples += std::uint64_t(total);
    progress.store(samples, std::memory_order_relaxed);
  }

 private:
  static constexpr std::uint8_t kDirectLight = 1, kEmitterRay = 2, kEmitterVisible = 4;

  /// Where sample number `n` of a tile's work belongs: pixel by pixel, row by row, and within
  /// a pixel samples first, first + 1, ...
  struct PieceLayout {
    Tile tile;
    int first;
    std::uint64_t per_pixel;

    int x(std::uint64_t n) const { return tile.x0 + int(n / per_pixel) % tile.width(); }
    int y(std::uint64_t n) const { return tile.y0 + int(n / per_pixel) / tile.width(); }
    std::uint32_t index(std::uint64_t n) const {
      return std::uint32_t(std::uint64_t(first) + n % per_pixel);
    }
  };

  static Ray ray_of(const ThreadState& state, int p) {
    return state.rays[std::size_t(p / RayBatch::kWidth)].get(p % RayBatch::kWidth);
  }
  static void set_ray(ThreadState& state, int p, const Ray& ray) {
    state.rays[std::size_t(p / RayBatch::kWidth)].set(p % RayBatch::kWidth, ray);
  }
  static SphereHit hit_of(const ThreadState& state, int p) {
    return state.hits[std::size_t(p / RayBatch::kWidth)].get(p % RayBatch::kWidth);
  }

  /// Lanes 0 .. count-1 of a block of eight holding the first `count` of the rest.
  static LaneMask lanes_below(int count) {
    return count >= RayBatch::kWidth ? RayBatch::kAllLanes : (LaneMask(1) << count) - 1;
  }

  /// Path p starts sample n: the camera ray through its point of the pixel, as
  /// ScalarExecution::add_samples makes it.
  GLINT_FLATTEN void start_path(ThreadState& state, int p, std::uint64_t n,
                                const PieceLayout& piece) const {
    const auto u = std::size_t(p);
    const int x = piece.x(n);
    const int y = piece.y(n);
    SamplerType& sampler = state.sampler[u];
    sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), piece.index(n),
                              std::uint32_t(settings_.samples_per_pixel), settings_.seed});
    Vec2 film(float(x) + 0.5f, float(y) + 0.5f);
    if constexpr (C::antialiasing::enabled)
      film += C::antialiasing::offset(sampler.next_2d(), settings_.antialias_sigma);
    set_ray(state, p, camera_.ray_through(film));
    state.throughput[u] = Color(1.0f);
    state.radiance[u] = Color(0.0f);
    state.depth[u] = 0;
    state.from[u] = Origin{};
    state.sample[u] = n;
  }

  GLINT_STAGE void trace_closest_hits(ThreadState& state, int live, TraceCounters& counters) const {
    counters.rays += std::uint64_t(live);
    for (int base = 0; base < live; base += RayBatch::kWidth) {
      const auto block = std::size_t(base / RayBatch::kWidth);
      scene_.closest_hits(state.rays[block], lanes_below(live - base), state.hits[block]);
    }
  }

  /// ChainEstimator's loop body for path p at the hit its ray found, up to the rays it needs
  /// traced: their light is added by gather_and_retire.
  GLINT_FLATTEN void shade(ThreadState& state, int p, TraceCounters& counters) const {
    const auto u = std::size_t(p);
    state.pending[u] = 0;
    state.ends[u] = 1;
    const SphereHit hit = hit_of(state, p);
    Color& radiance = state.radiance[u];
    const Color& throughput = state.throughput[u];
    if (hit.sphere == kNoSphere) {
      radiance += throughput * context_.background();
      return;
    }
    const Ray ray = ray_of(state, p);
    const SurfaceInteraction interaction = context_.interaction(ray, hit);
    if constexpr (kSamplesEmitters)
      radiance += throughput * context_.weighted_emission(ray, hit, interaction, state.from[u]);
    else
      radiance += throughput * interaction.material().emission;
    const ReportMaterial<C> material(interaction, ray.direction);
    SamplerType& sampler = state.sampler[u];
    const int depth = state.depth[u];
    state.shading_throughput[u] = throughput;
    if (material.has_lobe(Lobe::diffuse)) {
      state.pending[u] = kDirectLight;
      state.albedo[u] = material.albedo();
      state.irradiance[u] = Color(0.0f);
      context_.for_each_light_ray(interaction, [&](const Ray& shadow_ray, const Color& light) {
        ++counters.rays;
        queue_shadow_ray(state, p, shadow_ray, light);
      });
      if constexpr (kSamplesEmitters)
        if (depth < context_.max_depth()) {
          state.pending[u] |= kEmitterRay;
          state.emitter_light[u] = Color(0.0f);
          const std::optional<typename Context::EmitterRay> emitter = context_.emitter_ray(
              interaction, material, [&](const Vec3& direction) { return material.pdf(direction); },
              sampler);
          if (emitter) {
            ++counters.rays;
            state.emitter_light[u] = emitter->light;
            queue_emitter_ray(state, p, emitter->ray, emitter->emitter_sphere);
          }
        }
    }
    if (depth >= context_.max_depth() || !material.scatters()) return;
    const std::optional<float> continuation =
        context_.roulette_weight(depth, max_component(throughput), sampler);
    if (!continuation) return;

    const ScatterSample next = material.sample(sampler);
    if constexpr (kSamplesEmitters) state.from[u] = Context::origin_of(next);
    set_ray(state, p, Context::continue_ray(interaction, next.direction));
    state.throughput[u] *= next.tint * (next.factor * *continuation);
    state.depth[u] = depth + 1;
    state.ends[u] = 0;
  }

  void queue_shadow_ray(ThreadState& state, int p, const Ray& ray, const Color& light) const {
    if (state.shadow_count == kShadowQueue) trace_shadow_rays(state);
    const int q = state.shadow_count++;
    state.shadow_rays[std::size_t(q / RayBatch::kWidth)].set(q % RayBatch::kWidth, ray);
    state.shadow_owner[std::size_t(q)] = std::uint32_t(p);
    state.shadow_irradiance[std::size_t(q)] = light;
  }

  static void queue_emitter_ray(ThreadState& state, int p, const Ray& ray, std::uint32_t sphere) {
    const int q = state.emitter_count++;
    state.emitter_rays[std::size_t(q / RayBatch::kWidth)].set(q % RayBatch::kWidth, ray);
    state.emitter_owner[std::size_t(q)] = std::uint32_t(p);
    state.emitter_sphere[std::size_t(q)] = sphere;
  }

  /// Traces the queued shadow rays and adds the light of those not blocked to their paths'
  /// irradiance, in the order they were queued (a path's lights in the scene's order).
  GLINT_STAGE void trace_shadow_rays(ThreadState& state) const {
    const int count = state.shadow_count;
    for (int base = 0; base < count; base += RayBatch::kWidth) {
      const auto block = std::size_t(base / RayBatch::kWidth);
      const LaneMask active = lanes_below(count - base);
      const LaneMask blocked = scene_.occluded(state.shadow_rays[block], active);
      for_each_lane(active & ~blocked, [&](int lane) {
        const auto q = std::size_t(base + lane);
        state.irradiance[state.shadow_owner[q]] += state.shadow_irradiance[q];
      });
    }
    state.shadow_count = 0;
  }

  /// Traces the queued emitter rays: the light arrives where the first sphere hit is the
  /// emitter (PathContext::sample_emitter's test).
  GLINT_STAGE void trace_emitter_rays(ThreadState& state) const {
    const int count = state.emitter_count;
    for (int base = 0; base < count; base += RayBatch::kWidth) {
      const auto block = std::size_t(base / RayBatch::kWidth);
      const LaneMask active = lanes_below(count - base);
      HitBatch found;
      scene_.closest_hits(state.emitter_rays[block], active, found);
      for_each_lane(active, [&](int lane) {
        const auto q = std::size_t(base + lane);
        if (found.sphere[lane] == state.emitter_sphere[q])
          state.pending[state.emitter_owner[q]] |= kEmitterVisible;
      });
    }
    state.emitter_count = 0;
  }

  /// Adds the light the traced rays found to each path (ChainEstimator's terms, in its order)
  /// and retires the paths that ended, their radiance kept for add_finished; the paths that
  /// go on are moved down to fill the holes. Returns the number left.
  GLINT_STAGE static int gather_and_retire(ThreadState& state, int live) {
    for (int p = live - 1; p >= 0; --p) {
      const auto u = std::size_t(p);
      const std::uint8_t pending = state.pending[u];
      Color& radiance = state.radiance[u];
      if (pending & kDirectLight)
        radiance +=
            (state.shading_throughput[u] * state.albedo[u]) * (kInvPi * state.irradiance[u]);
      if (pending & kEmitterRay)
        radiance += state.shading_throughput[u] *
                    ((pending & kEmitterVisible) ? state.emitter_light[u] : Color(0.0f));
      if (!state.ends[u]) continue;
      const auto slot = std::size_t(state.sample[u] % std::uint64_t(kWindow));
      state.results[slot] = radiance;
      state.result_ready[slot] = 1;
      if (p != --live) move_path(state, live, p);
    }
    return live;
  }

  /// Moves path `from` (still going on) to place `to`, whose path has ended.
  static void move_path(ThreadState& state, int from, int to) {
    const auto f = std::size_t(from), t = std::size_t(to);
    set_ray(state, to, ray_of(state, from));
    state.throughput[t] = state.throughput[f];
    state.radiance[t] = state.radiance[f];
    state.depth[t] = state.depth[f];
    state.sample[t] = state.sample[f];
    state.from[t] = state.from[f];
    state.sampler[t] = state.sampler[f];
  }

  /// Adds the finished samples from `summed` on, in order, to their pixels' sums, up to the
  /// first one still in flight; returns where it stopped. A sample that is not finite is
  /// counted as invalid instead (ScalarExecution::add_samples's rule).
  GLINT_STAGE static std::uint64_t add_finished(ThreadState& state, const PieceLayout& piece,
                                                std::uint64_t summed, std::uint64_t started,
                                                PixelSums& sums, TraceCounters& counters) {
    for (; summed < started; ++summed) {
      const auto slot = std::size_t(summed % std::uint64_t(kWindow));
      if (!state.result_ready[slot]) break;
      state.result_ready[slot] = 0;
      const Color& sample = state.results[slot];
      if (std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z))
        sums.at(piece.x(summed), piece.y(summed)) += ColorSum(sample);
      else
        ++counters.invalid_samples;
    }
    return summed;
  }

  const Scene& scene_;
  PathContext<C> context_;
  Camera camera_;
  RenderSettings settings_;
};

}  // namespace glint

#undef GLINT_FLATTEN
#undef GLINT_STAGE
