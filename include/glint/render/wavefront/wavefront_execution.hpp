#pragma once
// WavefrontExecution<Config>: the execution model that advances many paths together. Each
// thread keeps a batch of paths in flight, in structure-of-arrays form (ThreadState), and runs
// every stage over the whole batch before the next: trace the rays to their closest hits eight
// at a time, shade every hit (emission, the light rays to queue, the next direction, roulette),
// trace the queued shadow and emitter rays eight at a time, add what they found, retire the
// finished paths and refill the batch with the next samples of the tile. This is the shape of
// pbrt-v4's wavefront/ integrator and Mitsuba 3's wavefront mode, on a CPU thread's scale.
//
// Each path follows ChainEstimator (render/estimators/chain.hpp): the same draws from the same
// sampler in the same order, and batched queries that answer exactly what the single-ray ones
// do. Shading runs eight paths at a time (shade_lanes: the hit, the material, the light rays,
// roulette and the next direction in SIMD lanes, and the sampler's starts and draws too where it
// has a lane-wise form: LanewiseSampler, LanewiseSamplerStart) wherever the
// configuration's policies have lane-wise forms (LanewisePolicies) and the build has AVX2;
// otherwise path by path with ChainEstimator's own code (shade_path). The lane-wise arithmetic
// is not the scalar code's to the last bit (a polynomial sin and cos, other multiply-adds), so
// images differ from the scalar renderer's by rounding, and a path that grazes an edge may go
// another way. A path's arithmetic never depends on the other paths of its batch, on its place
// in the batch or on the thread, and a pixel's samples are added to its sum in index order:
// the image is the same bit for bit whatever the thread count.

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <vector>

#include "glint/config.hpp"
#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/sampling.hpp"
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

#if defined(GLINT_AVX2)
/// Whether every policy the camera and shading stages call has a lane-wise form (eight values
/// at once): then WavefrontExecution runs those stages eight paths at a time. A user's policy
/// without one still renders, path by path. (The sphere shading is called lane by lane, and so
/// is a sampler without a Lanes form: see LanewiseSampler.)
template <typename C>
concept LanewisePolicies = requires(Vec2Lanes u, FloatLanes value, IntLanes depth, float sigma) {
  { C::antialiasing::offset(u, sigma) } -> std::same_as<Vec2Lanes>;
  { C::diffuse_sampling::sample(u) } -> std::same_as<BasicDirectionSample<FloatLanes>>;
  { C::diffuse_sampling::pdf(value) } -> std::same_as<FloatLanes>;
  { C::fresnel::reflectance(value, value, value) } -> std::same_as<FloatLanes>;
  { C::light_sampling::light_weight(value, value) } -> std::same_as<FloatLanes>;
  { C::path_termination::continue_probability(depth, value) } -> std::same_as<FloatLanes>;
};

/// A sampler with a form that draws for eight paths at once, in SIMD lanes: S::Lanes, which
/// loads and stores lane i from and to a sampler and draws for the lanes of a mask (the others
/// keep their state). Without one, WavefrontExecution draws path by path.
template <typename S>
concept LanewiseSampler = requires(typename S::Lanes lanes, const S& from, S& to, IntLanes mask) {
  lanes.set_lane(0, from);
  lanes.get_lane(0, to);
  { lanes.next_1d(mask) } -> std::same_as<FloatLanes>;
  { lanes.next_2d(mask) } -> std::same_as<Vec2Lanes>;
};

/// A LanewiseSampler whose Lanes form also starts the samplers of a mask's lanes at once, to
/// the state that S::start gives each. Without it the camera stage starts them one by one and
/// stores each in its lane.
template <typename S>
concept LanewiseSamplerStart = LanewiseSampler<S> &&
    requires(typename S::Lanes lanes, IntLanes mask, PixelSampleLanes s) {
  lanes.start(mask, s);
};
#endif

namespace detail {

/// The samplers of a thread's paths in flight, path p in slot p: one sampler per path, or
/// (kInLanes) the sampler's Lanes form, a block of eight paths per element, which the stages
/// draw from in place instead of loading and storing eight samplers around every stage.
template <typename S, bool kInLanes>
class PathSamplers {
 public:
  explicit PathSamplers(int paths) : samplers_(std::size_t(paths)) {}
  S& operator[](int p) { return samplers_[std::size_t(p)]; }
  void set(int p, const S& sampler) { samplers_[std::size_t(p)] = sampler; }
  void move(int from, int to) { samplers_[std::size_t(to)] = samplers_[std::size_t(from)]; }

 private:
  std::vector<S> samplers_;
};

#if defined(GLINT_AVX2)
template <typename S>
class PathSamplers<S, true> {
 public:
  explicit PathSamplers(int paths) : blocks_(std::size_t(paths / kLaneCount)) {}
  /// The samplers of paths base .. base+7 (base a multiple of eight).
  typename S::Lanes& block(int base) { return blocks_[std::size_t(base / kLaneCount)]; }
  void set(int p, const S& sampler) { block(p).set_lane(p % kLaneCount, sampler); }
  void move(int from, int to) {
    S sampler;
    block(from).get_lane(from % kLaneCount, sampler);
    set(to, sampler);
  }

 private:
  AlignedArray<typename S::Lanes> blocks_;
};
#endif

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
#if defined(GLINT_AVX2)
  /// x, y and index of samples n[0] .. n[7] in SIMD lanes. The quotients are taken in
  /// floating point and truncated: for integers with a + b below 2^p (p = 53 in a double, 24
  /// in a float), a / b lies at least 1/b below the next integer, farther than its rounding
  /// can carry it. Here n + per_pixel is below 2^41 (a tile has at most 2^20 pixels, a pass
  /// at most 2^20 samples), and the pixel n / per_pixel plus the tile's width below 2^21.
  void lanes(const std::uint64_t* n, PixelSampleLanes& sample) const {
    using Doubles = double __attribute__((vector_size(32)));
    Uint64Lanes samples;
    std::memcpy(&samples.low, n, sizeof samples.low);
    std::memcpy(&samples.high, n + 4, sizeof samples.high);
    const auto quotient = [&](Uint64Lanes::Half half) {
      // Without AVX-512's conversion: below 2^52, n is the mantissa of the double 2^52 + n.
      const Doubles value = std::bit_cast<Doubles>(half | 0x4330000000000000ULL) - 0x1p52;
      // Truncated by the instruction rather than a cast, which would be undefined where a lane
      // outside the caller's mask holds another tile's sample and the quotient overflows.
      return _mm256_cvttpd_epi32(__m256d(value / double(per_pixel)));
    };
    const auto pixel =
        std::bit_cast<IntLanes>(_mm256_set_m128i(quotient(samples.high), quotient(samples.low)));
    const int width = tile.width();
    const IntLanes row = __builtin_convertvector(
        __builtin_convertvector(pixel, FloatLanes) / float(width), IntLanes);
    sample.x = std::bit_cast<UintLanes>(tile.x0 + pixel - row * width);
    sample.y = std::bit_cast<UintLanes>(tile.y0 + row);
    sample.index = std::uint32_t(first) + samples.low_bits() -
                   std::bit_cast<UintLanes>(pixel) * std::uint32_t(per_pixel);
  }
#endif
};

}  // namespace detail

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
#if defined(GLINT_AVX2)
  /// Whether the camera and shading stages run eight paths at a time (see LanewisePolicies).
  static constexpr bool kUsesLanes = LanewisePolicies<C>;
  /// Whether the samplers are kept in their Lanes form (detail::PathSamplers).
  static constexpr bool kSamplersInLanes = kUsesLanes && LanewiseSampler<SamplerType>;
  /// Whether the camera stage starts eight samplers at once (LanewiseSamplerStart).
  static constexpr bool kStartsInLanes = kSamplersInLanes && LanewiseSamplerStart<SamplerType>;
#else
  static constexpr bool kUsesLanes = false;
  static constexpr bool kSamplersInLanes = false;
  static constexpr bool kStartsInLanes = false;
#endif

  /// Paths in flight per thread: enough that eight-ray batches stay full while paths end at
  /// different depths, few enough that the batch's state stays in the core's L2 cache.
  static constexpr int kPaths = 256;
  static_assert(kPaths % 64 == 0);  // gather_and_retire's words of ended paths
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

  /// Colours of the batch's paths, a column per channel, so that eight paths' colours load as
  /// three SIMD registers.
  class ColorColumns {
   public:
    explicit ColorColumns(int count) : x_(std::size_t(count)), y_(x_), z_(x_) {}
    Color get(int p) const {
      const auto u = std::size_t(p);
      return {x_[u], y_[u], z_[u]};
    }
    void set(int p, const Color& c) {
      const auto u = std::size_t(p);
      x_[u] = c.x;
      y_[u] = c.y;
      z_[u] = c.z;
    }
#if defined(GLINT_AVX2)
    Vec3Lanes lanes(int base) const {
      const auto u = std::size_t(base);
      return {load_lanes(&x_[u]), load_lanes(&y_[u]), load_lanes(&z_[u])};
    }
    void set_lanes(int base, const Vec3Lanes& c) {
      const auto u = std::size_t(base);
      store_lanes(&x_[u], c.x);
      store_lanes(&y_[u], c.y);
      store_lanes(&z_[u], c.z);
    }
#endif

   private:
    detail::AlignedArray<float> x_, y_, z_;
  };

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
          shadow_owner(kShadowQueue + RayBatch::kWidth),
          shadow_irradiance(kShadowQueue + RayBatch::kWidth),
          emitter_rays(kPaths / RayBatch::kWidth),
          emitter_owner(kPaths + RayBatch::kWidth),
          emitter_sphere(kPaths + RayBatch::kWidth),
          results(kWindow),
          result_ready(kWindow) {}

   private:
    friend class WavefrontExecution;

    // The paths in flight, 0 .. live-1. Rays and hits in blocks of eight for the batched
    // queries; path p is lane p % 8 of block p / 8.
    detail::AlignedArray<RayBatch> rays;
    detail::AlignedArray<HitBatch> hits;
    ColorColumns throughput;
    ColorColumns radiance;
    detail::AlignedArray<std::int32_t> depth;
    std::vector<std::uint64_t> sample;  ///< the path's sample, numbered within the tile's work
    std::vector<Origin> from;
    detail::PathSamplers<SamplerType, kSamplersInLanes> sampler;

    // What the current bounce waits for: light that the queued rays may bring, added once they
    // are traced, in ChainEstimator's order (point lights, then the emitter sample).
    ColorColumns shading_throughput;  ///< the throughput at the hit
    ColorColumns albedo;
    ColorColumns irradiance;
    ColorColumns emitter_light;
    // A lane of SIMD flags per path: eight paths' flags load and store as one register.
    detail::AlignedArray<std::int32_t> pending;  ///< kDirectLight | kEmitterRay | kEmitterVisible
    detail::AlignedArray<std::int32_t> ends;     ///< 1: the path ends after this bounce

    // The queues of rays to trace, and for each ray its path and what it brings. The arrays
    // beside the rays have eight entries to spare, which the lane-wise appends write past the
    // last one.
    detail::AlignedArray<RayBatch> shadow_rays;
    std::vector<std::uint32_t> shadow_owner;
    ColorColumns shadow_irradiance;
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
      const int refill = live;
      while (live < kPaths && started < total && started - summed < std::uint64_t(kWindow))
        state.sample[std::size_t(live++)] = started++;
      start_paths(state, refill, live, piece);
      if (live == 0) break;
      trace_closest_hits(state, live, counters);
      shade(state, live, counters);
      trace_shadow_rays(state);
      trace_emitter_rays(state);
      live = gather_and_retire(state, live);
      summed = add_finished(state, piece, summed, started, sums, counters);
    }
    samples += std::uint64_t(total);
    progress.store(samples, std::memory_order_relaxed);
  }

 private:
  static constexpr std::int32_t kDirectLight = 1, kEmitterRay = 2, kEmitterVisible = 4;

  using PieceLayout = detail::PieceLayout;

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

  /// Paths first .. last-1 start their samples (state.sample): the camera rays through their
  /// points of the pixels, as ScalarExecution::add_samples makes them.
  GLINT_STAGE void start_paths(ThreadState& state, int first, int last,
                               const PieceLayout& piece) const {
    if (first == last) return;
#if defined(GLINT_AVX2)
    if constexpr (kUsesLanes) {
      const int width = RayBatch::kWidth;
      for (int base = first - first % width; base < last; base += width) {
        const LaneMask lanes = lanes_below(last - base) & ~lanes_below(std::max(0, first - base));
        start_lanes(state, base, lanes, piece);
      }
    } else
#endif
    {
      for (int p = first; p < last; ++p)
        start_path(state, p, piece);
    }
  }

  /// Path p starts sample state.sample[p].
  GLINT_FLATTEN void start_path(ThreadState& state, int p, const PieceLayout& piece) const {
    const auto u = std::size_t(p);
    Vec2 film = start_sample(state, u, piece);
    if constexpr (C::antialiasing::enabled)
      film += C::antialiasing::offset(state.sampler[p].next_2d(), settings_.antialias_sigma);
    set_ray(state, p, camera_.ray_through(film));
    state.throughput.set(p, Color(1.0f));
    state.radiance.set(p, Color(0.0f));
  }

  /// Path p's sampler starts on state.sample[p], at depth 0 from the camera; returns the centre
  /// of the sample's pixel on the film.
  Vec2 start_sample(ThreadState& state, std::size_t p, const PieceLayout& piece) const {
    const std::uint64_t n = state.sample[p];
    const int x = piece.x(n);
    const int y = piece.y(n);
    SamplerType sampler;
    sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), piece.index(n),
                              std::uint32_t(settings_.samples_per_pixel), settings_.seed});
    state.sampler.set(int(p), sampler);
    state.depth[p] = 0;
    state.from[p] = Origin{};
    return Vec2(float(x) + 0.5f, float(y) + 0.5f);
  }

#if defined(GLINT_AVX2)
  /// start_path for the lanes of `lanes` of paths base .. base+7: the samplers at once where
  /// they can be (kStartsInLanes), else lane by lane; the filter offset and the camera rays in
  /// SIMD lanes.
  GLINT_FLATTEN void start_lanes(ThreadState& state, int base, LaneMask lanes,
                                 const PieceLayout& piece) const {
    const IntLanes mask = lanes_of_bits(lanes);
    Vec2Lanes film{};
    if constexpr (kStartsInLanes) {
      PixelSampleLanes sample{.samples_per_pixel = std::uint32_t(settings_.samples_per_pixel),
                              .seed = settings_.seed};
      piece.lanes(&state.sample[std::size_t(base)], sample);
      state.sampler.block(base).start(mask, sample);
      std::int32_t* depth = &state.depth[std::size_t(base)];
      store_lanes(depth, select(mask, broadcast(0), load_lanes(depth)));
      if constexpr (kSamplesEmitters) {
        // As in shade_lanes: the eight paths' BounceOrigins as one register.
        static_assert(sizeof(Origin) == sizeof(float) && std::is_trivially_copyable_v<Origin>);
        FloatLanes from;
        std::memcpy(&from, &state.from[std::size_t(base)], sizeof from);
        from = select(mask, broadcast(std::bit_cast<float>(Origin{})), from);
        std::memcpy(static_cast<void*>(&state.from[std::size_t(base)]), &from, sizeof from);
      }
      // start_sample's float(x) + 0.5f: the same two roundings in SIMD lanes.
      film = {__builtin_convertvector(std::bit_cast<IntLanes>(sample.x), FloatLanes) + 0.5f,
              __builtin_convertvector(std::bit_cast<IntLanes>(sample.y), FloatLanes) + 0.5f};
    } else {
      for_each_lane(lanes, [&](int i) {
        const Vec2 centre = start_sample(state, std::size_t(base + i), piece);
        film.x[i] = centre.x;
        film.y[i] = centre.y;
      });
    }
    if constexpr (C::antialiasing::enabled) {
      const Vec2Lanes u = SamplerBlock(state.sampler, base).next_2d(lanes);
      const Vec2Lanes offset = C::antialiasing::offset(u, settings_.antialias_sigma);
      film = {film.x + offset.x, film.y + offset.y};
    }
    RayLanes ray;
    ray.origin = Vec3Lanes::broadcast(camera_.position());
    camera_.rays_through(film, ray.direction, ray.t_min);
    ray.t_max = broadcast(kInfinity);
    ray.origin_sphere = broadcast(std::int32_t(kNoSphere));
    ray.heads_into_origin_sphere = broadcast(0);
    set_rays(state.rays[std::size_t(base / RayBatch::kWidth)], mask, ray);
    state.throughput.set_lanes(
        base, select(mask, Vec3Lanes::broadcast(Color(1.0f)), state.throughput.lanes(base)));
    state.radiance.set_lanes(
        base, select(mask, Vec3Lanes::broadcast(Color(0.0f)), state.radiance.lanes(base)));
  }
#endif

  GLINT_STAGE void trace_closest_hits(ThreadState& state, int live, TraceCounters& counters) const {
    counters.rays += std::uint64_t(live);
    for (int base = 0; base < live; base += RayBatch::kWidth) {
      const auto block = std::size_t(base / RayBatch::kWidth);
      scene_.closest_hits(state.rays[block], lanes_below(live - base), state.hits[block]);
    }
  }

  GLINT_STAGE void shade(ThreadState& state, int live, TraceCounters& counters) const {
    if constexpr (kUsesLanes) {
      for (int base = 0; base < live; base += RayBatch::kWidth)
        shade_lanes(state, base, lanes_below(live - base), counters);
    } else {
      for (int p = 0; p < live; ++p)
        shade_path(state, p, counters);
    }
  }

  /// ChainEstimator's loop body for path p at the hit its ray found, up to the rays it needs
  /// traced: their light is added by gather_and_retire.
  GLINT_FLATTEN void shade_path(ThreadState& state, int p, TraceCounters& counters) const {
    const auto u = std::size_t(p);
    state.pending[u] = 0;
    state.ends[u] = 1;
    const SphereHit hit = hit_of(state, p);
    Color radiance = state.radiance.get(p);
    const Color throughput = state.throughput.get(p);
    if (hit.sphere == kNoSphere) {
      radiance += throughput * context_.background();
      state.radiance.set(p, radiance);
      return;
    }
    const Ray ray = ray_of(state, p);
    const SurfaceInteraction interaction = context_.interaction(ray, hit);
    if constexpr (kSamplesEmitters)
      radiance += throughput * context_.weighted_emission(ray, hit, interaction, state.from[u]);
    else
      radiance += throughput * interaction.material().emission;
    state.radiance.set(p, radiance);
    const ReportMaterial<C> material(interaction, ray.direction);
    SamplerType& sampler = state.sampler[p];
    const int depth = state.depth[u];
    state.shading_throughput.set(p, throughput);
    if (material.has_lobe(Lobe::diffuse)) {
      state.pending[u] = kDirectLight;
      state.albedo.set(p, material.albedo());
      state.irradiance.set(p, Color(0.0f));
      context_.for_each_light_ray(interaction, [&](const Ray& shadow_ray, const Color& light) {
        ++counters.rays;
        queue_shadow_ray(state, p, shadow_ray, light);
      });
      if constexpr (kSamplesEmitters)
        if (depth < context_.max_depth()) {
          state.pending[u] |= kEmitterRay;
          state.emitter_light.set(p, Color(0.0f));
          const std::optional<typename Context::EmitterRay> emitter = context_.emitter_ray(
              interaction, material, [&](const Vec3& direction) { return material.pdf(direction); },
              sampler);
          if (emitter) {
            ++counters.rays;
            state.emitter_light.set(p, emitter->light);
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
    state.throughput.set(p, throughput * (next.tint * (next.factor * *continuation)));
    state.depth[u] = depth + 1;
    state.ends[u] = 0;
  }

#if defined(GLINT_AVX2)
  /// The samplers of paths base .. base+7 as one: drawn from in place in their Lanes form
  /// (kSamplersInLanes), one by one otherwise. Each draw is for the lanes of a mask, whose
  /// samplers alone advance; the values of the other lanes are unspecified.
  class SamplerBlock {
   public:
    SamplerBlock(detail::PathSamplers<SamplerType, kSamplersInLanes>& samplers, int base)
        : samplers_(samplers), base_(base) {}

    FloatLanes next_1d(LaneMask mask) {
      if constexpr (kSamplersInLanes) {
        return samplers_.block(base_).next_1d(lanes_of_bits(mask));
      } else {
        FloatLanes value = broadcast(0.0f);
        for_each_lane(mask, [&](int i) { value[i] = samplers_[base_ + i].next_1d(); });
        return value;
      }
    }
    Vec2Lanes next_2d(LaneMask mask) {
      if constexpr (kSamplersInLanes) {
        return samplers_.block(base_).next_2d(lanes_of_bits(mask));
      } else {
        Vec2Lanes value{broadcast(0.0f), broadcast(0.0f)};
        for_each_lane(mask, [&](int i) {
          const Vec2 u = samplers_[base_ + i].next_2d();
          value.x[i] = u.x;
          value.y[i] = u.y;
        });
        return value;
      }
    }

   private:
    detail::PathSamplers<SamplerType, kSamplersInLanes>& samplers_;
    int base_;
  };

  /// What shade_lanes reads of the spheres that eight paths hit, gathered lane by lane.
  struct SurfaceLanes {
    Vec3Lanes center;
    FloatLanes diffuse, mirror, transparent, ior, ior_outside;
    Vec3Lanes diffuse_color, mirror_color, transparent_color, emission;
    IntLanes fully_transparent;  ///< a mask
    LaneMask emitters = 0;       ///< lanes whose sphere is an emitter
    LaneMask patterned = 0;      ///< lanes whose sphere's colour depends on the point

    SurfaceLanes(const Scene& scene, const HitBatch& hits, LaneMask lanes) {
      // The 88 bytes of SurfaceProperties, read as 22 words: the material's seventeen floats,
      // the centre, ior_outside, a word whose two low bytes are the shading kind and
      // fully_transparent (and whose two high bytes are padding), and the emitter's index.
      // They are loaded in three blocks of eight consecutive words (the last two overlapping)
      // for the eight lanes at once; a lane without a hit reads zeros.
      static constexpr float kNoSurface[kRecordWords] = {};
      const float* record[kLaneCount];
      for (const float*& r : record)
        r = kNoSurface;
      for_each_lane(lanes, [&](int i) {
        record[i] = reinterpret_cast<const float*>(&scene.surface(hits.sphere[i]));
      });
      FloatLanes first[kLaneCount], second[kLaneCount], last[kLaneCount];
      const auto load_block = [&](int offset, FloatLanes(&columns)[kLaneCount]) {
        const float* rows[kLaneCount];
        for (int i = 0; i < kLaneCount; ++i)
          rows[i] = record[i] + offset;
        load_columns(rows, columns);
      };
      load_block(0, first);
      load_block(8, second);
      load_block(kRecordWords - 8, last);
      diffuse = first[0];
      diffuse_color = {first[1], first[2], first[3]};
      mirror = first[4];
      mirror_color = {first[5], first[6], first[7]};
      transparent = second[0];
      transparent_color = {second[1], second[2], second[3]};
      ior = second[4];
      emission = {second[5], second[6], second[7]};
      center = {last[2], last[3], last[4]};
      ior_outside = last[5];
      const auto flags = std::bit_cast<IntLanes>(last[6]);
      const auto emitter = std::bit_cast<IntLanes>(last[7]);
      patterned = lanes & lane_bits((flags & 0xff) != std::int32_t(ShadingKind::uniform));
      fully_transparent = (flags & 0xff00) != 0;
      emitters = lanes & lane_bits(emitter != std::int32_t(kNotAnEmitter));
    }

   private:
    static constexpr int kRecordWords = 22;
    // The layout the loads above read.
    static_assert(offsetof(SurfaceProperties, material) == 0 && offsetof(Material, diffuse) == 0 &&
                  offsetof(Material, diffuse_color) == 4 && offsetof(Material, mirror) == 16 &&
                  offsetof(Material, mirror_color) == 20 && offsetof(Material, transparent) == 32 &&
                  offsetof(Material, transparent_color) == 36 && offsetof(Material, ior) == 48 &&
                  offsetof(Material, emission) == 52 && offsetof(SurfaceProperties, center) == 64 &&
                  offsetof(SurfaceProperties, ior_outside) == 76 &&
                  offsetof(SurfaceProperties, shading) == 80 && sizeof(ShadingKind) == 1 &&
                  offsetof(SurfaceProperties, fully_transparent) == 81 && sizeof(bool) == 1 &&
                  offsetof(SurfaceProperties, emitter) == 84 &&
                  sizeof(SurfaceProperties) == kRecordWords * sizeof(float));
  };

  /// shade_path for the paths base .. base+7 of `lanes` at once: the same steps and the same
  /// draws in the same order for each path, the arithmetic in SIMD lanes (masks where paths
  /// differ), the draws and the queueing of rays lane by lane.
  GLINT_FLATTEN void shade_lanes(ThreadState& state, int base, LaneMask lanes,
                                 TraceCounters& counters) const {
    const auto block = std::size_t(base / RayBatch::kWidth);
    const RayBatch& ray = state.rays[block];
    const HitBatch& hit = state.hits[block];
    IntLanes sphere;
    std::memcpy(&sphere, hit.sphere, sizeof sphere);
    const LaneMask hits = lanes & lane_bits(sphere != std::int32_t(kNoSphere));
    const IntLanes hit_mask = lanes_of_bits(hits);
    const Vec3Lanes throughput = state.throughput.lanes(base);
    Vec3Lanes radiance = state.radiance.lanes(base);
    radiance = select(hit_mask, radiance,
                      radiance + throughput * Vec3Lanes::broadcast(context_.background()));
    std::int32_t* const pending = &state.pending[std::size_t(base)];
    std::int32_t* const ends = &state.ends[std::size_t(base)];
    store_lanes(pending, broadcast(0));
    store_lanes(ends, broadcast(1));
    if (hits == 0) {
      state.radiance.set_lanes(base, radiance);
      return;
    }

    // The hit, as Scene::surface_hit and detail::interface_at set it up.
    const SurfaceLanes surface(scene_, hit, hits);
    const Vec3Lanes direction = {load_lanes(ray.direction_x), load_lanes(ray.direction_y),
                                 load_lanes(ray.direction_z)};
    const Vec3Lanes origin = {load_lanes(ray.origin_x), load_lanes(ray.origin_y),
                              load_lanes(ray.origin_z)};
    const Vec3Lanes point = origin + load_lanes(hit.t) * direction;
    const Vec3Lanes normal = normalize(point - surface.center);
    const FloatLanes cos_out = dot(direction, normal);
    const IntLanes from_inside = cos_out > 0.0f;
    const Vec3Lanes facing = select(from_inside, -normal, normal);
    const FloatLanes cos_incident = abs(cos_out);

    // Emission, weighted against light sampling where an emitter was reached by a bounce.
    FloatLanes emission_weight = broadcast(1.0f);
    if constexpr (kSamplesEmitters)
      for_each_lane(surface.emitters, [&](int i) {
        const int p = base + i;
        const BounceOrigin& from = state.from[std::size_t(p)];
        if (!(from.pdf > 0.0f)) return;
        const Ray lane_ray = ray_of(state, p);
        const SphereHit lane_hit = hit_of(state, p);
        const SurfaceInteraction interaction = context_.interaction(lane_ray, lane_hit);
        emission_weight[i] = context_.emission_weight(lane_ray, lane_hit, interaction,
                                                      interaction.surface->emitter, from);
      });
    radiance =
        select(hit_mask, radiance + throughput * (surface.emission * emission_weight), radiance);
    state.radiance.set_lanes(base, radiance);
    state.shading_throughput.set_lanes(base, throughput);

    // The material (ReportMaterial's terms).
    Vec3Lanes albedo = surface.diffuse_color;
    for_each_lane(surface.patterned & hits, [&](int i) {
      const SurfaceProperties& s = scene_.surface(hit.sphere[i]);
      albedo.set_lane(
          i, C::sphere_shading::color(s.shading, s.material.diffuse_color, normal.lane(i)));
    });
    const IntLanes has_diffuse = hit_mask & (surface.diffuse > 0.0f);
    albedo = select(has_diffuse, surface.diffuse * albedo, Vec3Lanes::broadcast(Color(0.0f)));
    const FloatLanes total = surface.diffuse + surface.mirror + surface.transparent;
    const IntLanes depth = load_lanes(&state.depth[std::size_t(base)]);
    const LaneMask diffuse_lanes = lane_bits(has_diffuse);
    SamplerBlock draws(state.sampler, base);

    // Light: the point lights' shadow rays and the emitter sample, at diffuse hits.
    if (diffuse_lanes != 0) {
      state.albedo.set_lanes(base, albedo);
      state.irradiance.set_lanes(base, Vec3Lanes::broadcast(Color(0.0f)));
      store_lanes(pending, has_diffuse & kDirectLight);
      for (const PointLight& light : scene_.lights()) {
        const Vec3Lanes to_light = Vec3Lanes::broadcast(light.position) - point;
        const FloatLanes distance2 = dot(to_light, to_light);
        const FloatLanes distance = sqrt(distance2);
        const Vec3Lanes toward = to_light / distance;
        const FloatLanes cosine = dot(toward, facing);
        const LaneMask lit = diffuse_lanes & lane_bits(cosine > 0.0f);
        if (lit == 0) continue;
        const Vec3Lanes irradiance =
            ((light.intensity * cosine) / distance2) * Vec3Lanes::broadcast(light.color);
        counters.rays += std::uint64_t(std::popcount(lit));
        queue_shadow_rays(
            state, base, lit,
            {point, toward, broadcast(0.0f), distance, sphere, dot(toward, normal) < 0.0f},
            irradiance);
      }
      if constexpr (kSamplesEmitters)
        sample_emitters_lanes(state, base, diffuse_lanes & lane_bits(depth < context_.max_depth()),
                              sphere, point, normal, facing, from_inside, albedo,
                              surface.diffuse / total, draws, counters);
    }

    // Roulette and the lobe, in ChainEstimator's order.
    LaneMask going_on = hits & lane_bits((depth < context_.max_depth()) & (total > 0.0f));
    FloatLanes continuation = broadcast(1.0f);
    if constexpr (C::path_termination::uses_roulette) {
      const FloatLanes p =
          C::path_termination::continue_probability(depth, max_component(throughput));
      const LaneMask played = going_on & lane_bits(p < 1.0f);
      if (played != 0) going_on &= ~(played & lane_bits(draws.next_1d(played) >= p));
      continuation = select(p < 1.0f, 1.0f / p, continuation);
    }
    if (going_on == 0) return;
    const FloatLanes u_lobe = draws.next_1d(going_on) * total;
    const IntLanes choose_diffuse = u_lobe < surface.diffuse;
    const IntLanes choose_mirror = ~choose_diffuse & (u_lobe < surface.diffuse + surface.mirror);
    const IntLanes choose_transmission = ~(choose_diffuse | choose_mirror);

    const Vec3Lanes reflected = direction + (2.0f * cos_incident) * facing;
    const LaneMask diffuse_draws = going_on & lane_bits(choose_diffuse);
    // One draw per path: the diffuse direction's or Fresnel's (never both).
    const Vec2Lanes u_diffuse = draws.next_2d(diffuse_draws);

    // Transmission: refraction, or reflection on total internal reflection or by Fresnel
    // (worked out only where some path transmits).
    IntLanes reflect = broadcast(0);
    Vec3Lanes refracted = reflected;
    if ((going_on & lane_bits(choose_transmission)) != 0) {
      const FloatLanes eta_incident = select(from_inside, surface.ior, surface.ior_outside);
      const FloatLanes eta_transmitted = select(from_inside, surface.ior_outside, surface.ior);
      const FloatLanes eta = eta_incident / eta_transmitted;
      const FloatLanes sin2_transmitted = eta * eta * (1.0f - cos_incident * cos_incident);
      const IntLanes total_internal = sin2_transmitted >= 1.0f;
      const FloatLanes cos_transmitted = sqrt(max(broadcast(0.0f), 1.0f - sin2_transmitted));
      refracted = normalize(eta * direction + (eta * cos_incident - cos_transmitted) * facing);
      reflect = total_internal;
      if constexpr (C::fresnel::enabled) {
        const IntLanes by_fresnel =
            choose_transmission & ~total_internal & surface.fully_transparent;
        const FloatLanes reflectance =
            C::fresnel::reflectance(cos_incident, eta_incident, eta_transmitted);
        const LaneMask fresnel_draws = going_on & lane_bits(by_fresnel);
        if (fresnel_draws != 0)
          reflect |= lanes_of_bits(fresnel_draws) & (draws.next_1d(fresnel_draws) < reflectance);
      }
    }

    // Diffuse: a direction from C::diffuse_sampling in the frame of the facing normal.
    const BasicDirectionSample<FloatLanes> diffuse_sample = C::diffuse_sampling::sample(u_diffuse);
    const Vec3Lanes diffuse_direction =
        BasicFrame<Vec3Lanes>::around(facing).to_world(diffuse_sample.local_direction);

    const Vec3Lanes next_direction = select(choose_diffuse, diffuse_direction,
                                            select(choose_mirror | reflect, reflected, refracted));
    const Vec3Lanes tint =
        select(choose_diffuse, albedo,
               select(choose_mirror, surface.mirror_color, surface.transparent_color));
    const FloatLanes factor =
        select(choose_diffuse, diffuse_sample.weight * kInvPi * total / surface.diffuse, total);
    if constexpr (kSamplesEmitters) {
      const FloatLanes pdf =
          C::diffuse_sampling::pdf(diffuse_sample.local_direction.z) * (surface.diffuse / total);
      // The eight paths' BounceOrigins (a float each) as one register.
      static_assert(sizeof(Origin) == sizeof(float) && std::is_trivially_copyable_v<Origin>);
      FloatLanes from;
      std::memcpy(&from, &state.from[std::size_t(base)], sizeof from);
      from = select(lanes_of_bits(going_on), select(choose_diffuse, pdf, broadcast(0.0f)), from);
      std::memcpy(static_cast<void*>(&state.from[std::size_t(base)]), &from, sizeof from);
    }

    const IntLanes continues = lanes_of_bits(going_on);
    state.throughput.set_lanes(
        base, select(continues, throughput * (tint * (factor * continuation)), throughput));
    store_lanes(&state.depth[std::size_t(base)], select(continues, depth + 1, depth));
    set_rays(state.rays[block], continues,
             {point, next_direction, broadcast(0.0f), broadcast(kInfinity), sphere,
              dot(next_direction, normal) < 0.0f});
    store_lanes(ends, ~continues & 1);
  }

  /// Eight rays in SIMD lanes (Ray's fields).
  struct RayLanes {
    Vec3Lanes origin, direction;
    FloatLanes t_min, t_max;
    IntLanes origin_sphere;
    IntLanes heads_into_origin_sphere;  ///< a mask
  };

  /// Sets the lanes of `mask` of `rays` to `to`, as RayBatch::set would lane by lane.
  static void set_rays(RayBatch& rays, IntLanes mask, const RayLanes& to) {
    const auto update = [&](float* column, FloatLanes value) {
      store_lanes(column, select(mask, value, load_lanes(column)));
    };
    update(rays.origin_x, to.origin.x);
    update(rays.origin_y, to.origin.y);
    update(rays.origin_z, to.origin.z);
    update(rays.direction_x, to.direction.x);
    update(rays.direction_y, to.direction.y);
    update(rays.direction_z, to.direction.z);
    update(rays.t_min, to.t_min);
    update(rays.t_max, to.t_max);
    IntLanes sphere;
    std::memcpy(&sphere, rays.origin_sphere, sizeof sphere);
    sphere = select(mask, to.origin_sphere, sphere);
    std::memcpy(rays.origin_sphere, &sphere, sizeof sphere);
    const LaneMask bits = lane_bits(mask);
    rays.heads_into_origin_sphere =
        (rays.heads_into_origin_sphere & ~bits) | (lane_bits(to.heads_into_origin_sphere) & bits);
  }

  /// The emitter sample of PathContext::emitter_ray for the lanes of `lanes` (diffuse hits
  /// from which a bounce may follow): the draws lane by lane, the rest in SIMD lanes.
  void sample_emitters_lanes(ThreadState& state, int base, LaneMask lanes, IntLanes hit_sphere,
                             const Vec3Lanes& point, const Vec3Lanes& normal,
                             const Vec3Lanes& facing, IntLanes from_inside, const Vec3Lanes& albedo,
                             FloatLanes diffuse_probability, SamplerBlock& draws,
                             TraceCounters& counters) const {
    if (lanes == 0) return;
    std::int32_t* const pending = &state.pending[std::size_t(base)];
    store_lanes(pending, load_lanes(pending) | (lanes_of_bits(lanes) & kEmitterRay));
    state.emitter_light.set_lanes(base, Vec3Lanes::broadcast(Color(0.0f)));
    const EmitterTable& emitters = scene_.emitters();
    if (emitters.empty()) return;
    const FloatLanes u_choice = draws.next_1d(lanes);
    const Vec2Lanes u = draws.next_2d(lanes);
    // The chosen emitters' eight words (centre, radius, radiance, sphere) as one 8x8 transpose.
    // Every lane's index is a valid one, whatever its u, so every lane may read its record.
    static_assert(offsetof(SphereEmitter, center) == 0 && offsetof(SphereEmitter, radius) == 12 &&
                  offsetof(SphereEmitter, radiance) == 16 &&
                  offsetof(SphereEmitter, sphere) == 28 && sizeof(SphereEmitter) == 32);
    const IntLanes chosen = emitters.choose_lanes(u_choice);
    const float* records[kLaneCount];
    FloatLanes probability;
    for (int i = 0; i < kLaneCount; ++i) {
      const auto index = std::uint32_t(chosen[i]);
      records[i] = reinterpret_cast<const float*>(&emitters[index]);
      probability[i] = emitters.probability(index);
    }
    FloatLanes words[kLaneCount];
    load_columns(records, words);
    const Vec3Lanes center{words[0], words[1], words[2]};
    const FloatLanes radius = words[3];
    const Vec3Lanes radiance{words[4], words[5], words[6]};
    const auto emitter_sphere = std::bit_cast<IntLanes>(words[7]);
    const LaneMask on_emitter = lanes & lane_bits(emitter_sphere == hit_sphere);
    // SphereEmitter::view_from lane by lane: from outside, from inside (or from the emitter's
    // inner surface), or from its outer surface (none). Lanes not sampled count as outside,
    // so that they alone never make the area branch run.
    const Vec3Lanes offset = point - center;
    const IntLanes on = lanes_of_bits(on_emitter);
    const IntLanes outside =
        ~lanes_of_bits(lanes) | (~on & (dot(offset, offset) > radius * radius));
    const IntLanes none = on & ~from_inside;
    const BasicEmitterSample<FloatLanes> sample =
        sample_sphere_emitter(center, radius, point, outside, none, u);
    const Vec3Lanes& toward = sample.direction;
    const FloatLanes& pdf = sample.pdf;
    const FloatLanes cosine = dot(toward, facing);
    const Vec3Lanes reflected =
        select(cosine > 0.0f, albedo * (kInvPi * cosine), Vec3Lanes::broadcast(Color(0.0f)));
    const IntLanes arrives =
        sample.valid & (pdf > 0.0f) &
        ((reflected.x != 0.0f) | (reflected.y != 0.0f) | (reflected.z != 0.0f));
    const LaneMask sampled = lanes & lane_bits(arrives);
    if (sampled == 0) return;
    const FloatLanes light_pdf = probability * pdf;
    const FloatLanes weight = C::light_sampling::light_weight(
        light_pdf, diffuse_probability * C::diffuse_sampling::pdf(cosine));
    const Vec3Lanes light = reflected * radiance * (weight / light_pdf);
    state.emitter_light.set_lanes(
        base, select(lanes_of_bits(sampled), light, Vec3Lanes::broadcast(Color(0.0f))));
    counters.rays += std::uint64_t(std::popcount(sampled));
    queue_emitter_rays(state, base, sampled,
                       {point, toward, broadcast(0.0f), broadcast(kInfinity), hit_sphere,
                        dot(toward, normal) < 0.0f},
                       emitter_sphere);
  }

  /// Appends the rays of lanes `lanes` of `rays` to the queue `blocks`, which holds `count`
  /// rays, in lane order: what RayBatch::set would write lane by lane, a column at a time. The
  /// queue has room for them.
  static void append_rays(RayBatch* blocks, int count, LaneMask lanes, IntLanes packing,
                          const RayLanes& rays) {
    const int at = count % RayBatch::kWidth;
    const int end = at + std::popcount(lanes);
    RayBatch& last = blocks[count / RayBatch::kWidth];
    RayBatch* const next = end > RayBatch::kWidth ? &last + 1 : nullptr;
    const IntLanes order = rotated_order(packing, at);
    const IntLanes lane = lane_indices();
    const IntLanes into_last = (lane >= at) & (lane < end);
    const IntLanes into_next = lane < end - RayBatch::kWidth;
    const auto append = [&](float(RayBatch::*column)[RayBatch::kWidth], FloatLanes value) {
      value = permute(value, order);
      store_lanes(last.*column, select(into_last, value, load_lanes(last.*column)));
      if (next) store_lanes(next->*column, select(into_next, value, load_lanes(next->*column)));
    };
    append(&RayBatch::origin_x, rays.origin.x);
    append(&RayBatch::origin_y, rays.origin.y);
    append(&RayBatch::origin_z, rays.origin.z);
    append(&RayBatch::direction_x, rays.direction.x);
    append(&RayBatch::direction_y, rays.direction.y);
    append(&RayBatch::direction_z, rays.direction.z);
    append(&RayBatch::t_min, rays.t_min);
    append(&RayBatch::t_max, rays.t_max);
    const auto append_ids = [&](RayBatch& batch, IntLanes into, IntLanes value) {
      IntLanes ids;
      std::memcpy(&ids, batch.origin_sphere, sizeof ids);
      ids = select(into, value, ids);
      std::memcpy(batch.origin_sphere, &ids, sizeof ids);
    };
    const IntLanes origin_sphere = permute(rays.origin_sphere, order);
    append_ids(last, into_last, origin_sphere);
    if (next) append_ids(*next, into_next, origin_sphere);
    const LaneMask heads_in = lane_bits(permute(rays.heads_into_origin_sphere, order));
    const auto merge = [&](RayBatch& batch, IntLanes into) {
      const LaneMask bits = lane_bits(into);
      batch.heads_into_origin_sphere = (batch.heads_into_origin_sphere & ~bits) | (heads_in & bits);
    };
    merge(last, into_last);
    if (next) merge(*next, into_next);
  }

  /// Stores the lanes that `packing` (a packing_order) moves first, lowest first, at to[0],
  /// to[1], ... (and unspecified values up to to[7]).
  template <typename T>
  static void append_values(T* to, IntLanes packing, IntLanes values) {
    static_assert(sizeof(T) == sizeof(std::int32_t));
    const IntLanes packed = permute(values, packing);
    std::memcpy(to, &packed, sizeof packed);
  }

  /// queue_shadow_ray for the lanes of `lanes` of paths base .. base+7, in lane order.
  void queue_shadow_rays(ThreadState& state, int base, LaneMask lanes, const RayLanes& rays,
                         const Vec3Lanes& light) const {
    if (state.shadow_count + std::popcount(lanes) > kShadowQueue) trace_shadow_rays(state);
    const int q = state.shadow_count;
    const IntLanes packing = packing_order(lanes);
    append_rays(state.shadow_rays.data(), q, lanes, packing, rays);
    append_values(&state.shadow_owner[std::size_t(q)], packing, base + lane_indices());
    state.shadow_irradiance.set_lanes(
        q, {permute(light.x, packing), permute(light.y, packing), permute(light.z, packing)});
    state.shadow_count += std::popcount(lanes);
  }

  /// queue_emitter_ray for the lanes of `lanes` of paths base .. base+7, in lane order.
  static void queue_emitter_rays(ThreadState& state, int base, LaneMask lanes, const RayLanes& rays,
                                 IntLanes emitter_sphere) {
    const int q = state.emitter_count;
    const IntLanes packing = packing_order(lanes);
    append_rays(state.emitter_rays.data(), q, lanes, packing, rays);
    append_values(&state.emitter_owner[std::size_t(q)], packing, base + lane_indices());
    append_values(&state.emitter_sphere[std::size_t(q)], packing, emitter_sphere);
    state.emitter_count += std::popcount(lanes);
  }

#endif  // GLINT_AVX2

  void queue_shadow_ray(ThreadState& state, int p, const Ray& ray, const Color& light) const {
    if (state.shadow_count == kShadowQueue) trace_shadow_rays(state);
    const int q = state.shadow_count++;
    state.shadow_rays[std::size_t(q / RayBatch::kWidth)].set(q % RayBatch::kWidth, ray);
    state.shadow_owner[std::size_t(q)] = std::uint32_t(p);
    state.shadow_irradiance.set(q, light);
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
        const auto owner = int(state.shadow_owner[q]);
        state.irradiance.set(owner,
                             state.irradiance.get(owner) + state.shadow_irradiance.get(int(q)));
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
      LaneMask visible = 0;
#if defined(GLINT_AVX2)
      IntLanes found_sphere, emitter_sphere;
      std::memcpy(&found_sphere, found.sphere, sizeof found_sphere);
      std::memcpy(&emitter_sphere, &state.emitter_sphere[std::size_t(base)], sizeof emitter_sphere);
      visible = active & lane_bits(found_sphere == emitter_sphere);
#else
      for_each_lane(active, [&](int lane) {
        if (found.sphere[lane] == state.emitter_sphere[std::size_t(base + lane)])
          visible |= LaneMask(1) << lane;
      });
#endif
      for_each_lane(visible, [&](int lane) {
        state.pending[state.emitter_owner[std::size_t(base + lane)]] |= kEmitterVisible;
      });
    }
    state.emitter_count = 0;
  }

  /// Adds the light the traced rays found to each path (ChainEstimator's terms, in its order)
  /// and retires the paths that ended, their radiance kept for add_finished; the paths that
  /// go on are moved down to fill the holes. Returns the number left.
  GLINT_STAGE static int gather_and_retire(ThreadState& state, int live) {
#if defined(GLINT_AVX2)
    for (int base = 0; base < live; base += RayBatch::kWidth)
      gather_lanes(state, base);
#else
    for (int p = 0; p < live; ++p)
      gather_path(state, p);
#endif
    // The ended paths as bits, visited from the last down: a path moved into a hole comes from
    // above it, where every path has been visited, so the bits taken first stay true. (A test of
    // each path's flag instead is a branch that mispredicts about once per ended path.)
    std::uint64_t ended[kPaths / 64] = {};
    for (int base = 0; base < live; base += RayBatch::kWidth) {
      std::uint64_t bits = 0;
#if defined(GLINT_AVX2)
      bits = lane_bits(load_lanes(&state.ends[std::size_t(base)]) != 0);
#else
      for (int i = 0; i < RayBatch::kWidth; ++i)
        bits |= std::uint64_t(state.ends[std::size_t(base + i)] != 0) << i;
#endif
      ended[base / 64] |= (bits & lanes_below(live - base)) << (base % 64);
    }
    for (int word = (live - 1) / 64; word >= 0; --word)
      for (std::uint64_t bits = ended[word]; bits != 0;) {
        const int top = 63 - std::countl_zero(bits);
        bits &= ~(std::uint64_t(1) << top);
        const int p = 64 * word + top;
        const auto slot = std::size_t(state.sample[std::size_t(p)] % std::uint64_t(kWindow));
        state.results[slot] = state.radiance.get(p);
        state.result_ready[slot] = 1;
        if (p != --live) move_path(state, live, p);
      }
    return live;
  }

  static void gather_path(ThreadState& state, int p) {
    const std::int32_t pending = state.pending[std::size_t(p)];
    Color radiance = state.radiance.get(p);
    if (pending & kDirectLight)
      radiance += (state.shading_throughput.get(p) * state.albedo.get(p)) *
                  (kInvPi * state.irradiance.get(p));
    if (pending & kEmitterRay)
      radiance += state.shading_throughput.get(p) *
                  ((pending & kEmitterVisible) ? state.emitter_light.get(p) : Color(0.0f));
    state.radiance.set(p, radiance);
  }

#if defined(GLINT_AVX2)
  /// gather_path for paths base .. base+7 (those beyond the live ones are left as they are:
  /// their pending flags are clear).
  static void gather_lanes(ThreadState& state, int base) {
    const IntLanes pending = load_lanes(&state.pending[std::size_t(base)]);
    if (lane_bits(pending != 0) == 0) return;
    const Vec3Lanes zero = Vec3Lanes::broadcast(Color(0.0f));
    const Vec3Lanes throughput = state.shading_throughput.lanes(base);
    Vec3Lanes radiance = state.radiance.lanes(base);
    radiance = select((pending & kDirectLight) != 0,
                      radiance + (throughput * state.albedo.lanes(base)) *
                                     (kInvPi * state.irradiance.lanes(base)),
                      radiance);
    radiance = select((pending & kEmitterRay) != 0,
                      radiance + throughput * select((pending & kEmitterVisible) != 0,
                                                     state.emitter_light.lanes(base), zero),
                      radiance);
    state.radiance.set_lanes(base, radiance);
  }
#endif

  /// Moves path `from` (still going on) to place `to`, whose path has ended.
  static void move_path(ThreadState& state, int from, int to) {
    const auto f = std::size_t(from), t = std::size_t(to);
    set_ray(state, to, ray_of(state, from));
    state.throughput.set(to, state.throughput.get(from));
    state.radiance.set(to, state.radiance.get(from));
    state.depth[t] = state.depth[f];
    state.sample[t] = state.sample[f];
    state.from[t] = state.from[f];
    state.sampler.move(from, to);
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
