#pragma once
// WavefrontExecution<Config>: the execution model that advances many paths together. Each
// thread keeps a batch of paths in flight, in structure-of-arrays form (ThreadState), and runs
// every stage over the whole batch before the next: trace the rays to their closest hits
// sixteen at a time with AVX-512 (eight with AVX2), shade every hit (emission, the light rays to
// queue, the next direction, roulette), trace the queued shadow and emitter rays as many at a
// time, add what they found, retire the
// finished paths and refill the batch with the next samples of the tile. This is the shape of
// pbrt-v4's wavefront/ integrator and Mitsuba 3's wavefront mode, on a CPU thread's scale.
//
// Each path follows ChainEstimator (render/estimators/chain.hpp), whose step() the shading
// stage calls for kWidth paths at a time: a SIMD register's paths (16 with AVX-512, 8 with
// AVX2) where the configuration's policies have forms for that many lanes (PoliciesAtWidth),
// else one. The light rays a
// step asks for are queued and traced in batches, and what they bring is added by
// ChainEstimator::add_light, as the scalar renderer does for one path: the same operations in
// the same order at every width, so the wavefront gives the scalar renderer's image bit for
// bit. A path's arithmetic never depends on the other paths of its batch, on its place in the
// batch or on the thread, and a pixel's samples are added to its sum in index order: the image
// is the same whatever the thread count.

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "glint/config.hpp"
#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/sampling.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/chain.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/scattering.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"

// Everything the shading and camera stages call is inlined into them: the step's material,
// warps and samplers' draws are short next to a call's cost in registers spilled for 8 or 16
// lanes, and GCC leaves them out of line by its size limits otherwise. (The images do not
// depend on it: glint compiles with -ffp-contract=off.)
#if defined(__GNUC__) && !defined(__clang__)
#define GLINT_FLATTEN [[gnu::flatten]]
#else
#define GLINT_FLATTEN
#endif

// Each stage that runs once per batch stays a function of its own: a call per 256 paths costs
// nothing, and a profile (perf report) then gives every stage's share of the time by name.
#define GLINT_STAGE [[gnu::noinline]]

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Whether variant C can be rendered by WavefrontRenderer: its camera paths follow one lobe per
/// bounce, so a sample is one path. (The report's tree follows every lobe: a sample is a tree of
/// rays; light tracing follows paths from the lights.)
template <typename C>
concept WavefrontConfig = RenderConfig<C> && std::same_as<typename C::estimator, PathTracing>;

/// Whether every policy the camera and shading stages call has a form for the lanes of a
/// Float<W> (W paths at once): then WavefrontExecution runs those stages W paths at a time. A
/// user's policy written for one path still renders, path by path. (The sphere shading is
/// called lane by lane, and so is a sampler without a Wide form: see WideSampler.)
template <typename C, int W>
concept PoliciesAtWidth = requires(Vec2For<Float<W>> u, Float<W> value, Int<W> depth, float sigma) {
  { C::antialiasing::offset(u, sigma) } -> std::same_as<Vec2For<Float<W>>>;
  { C::diffuse_sampling::sample(u) } -> std::same_as<BasicDirectionSample<Float<W>>>;
  { C::diffuse_sampling::pdf(value) } -> std::same_as<Float<W>>;
  { C::fresnel::reflectance(value, value, value) } -> std::same_as<Float<W>>;
  { C::light_sampling::light_weight(value, value) } -> std::same_as<Float<W>>;
  { C::path_termination::continue_probability(depth, value) } -> std::same_as<Float<W>>;
};

namespace detail {

/// The samplers of a thread's paths in flight, path p in slot p: one sampler per path (W = 1),
/// or the sampler's Wide<W> form, a block of W paths per element, which the stages draw from in
/// place instead of loading and storing W samplers around every stage.
template <typename S, int W>
class PathSamplers {
 public:
  explicit PathSamplers(int paths) : blocks_(std::size_t(paths / W)) {}
  /// The samplers of paths base .. base + W - 1 (base a multiple of W).
  typename S::template Wide<W>& block(int base) { return blocks_[std::size_t(base / W)]; }
  void set(int p, const S& sampler) { block(p).set_lane(p % W, sampler); }
  void move(int from, int to) {
    S sampler;
    block(from).get_lane(from % W, sampler);
    set(to, sampler);
  }

 private:
  AlignedArray<typename S::template Wide<W>> blocks_;
};

template <typename S>
class PathSamplers<S, 1> {
 public:
  explicit PathSamplers(int paths) : samplers_(std::size_t(paths)) {}
  S& operator[](int p) { return samplers_[std::size_t(p)]; }
  void set(int p, const S& sampler) { samplers_[std::size_t(p)] = sampler; }
  void move(int from, int to) { samplers_[std::size_t(to)] = samplers_[std::size_t(from)]; }

 private:
  std::vector<S> samplers_;
};

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

  /// Sample `n`'s pixel and its place among the pixel's samples, which step to those of n + 1
  /// without the divisions of x(), y() and index(): a stage's samples are mostly consecutive.
  struct Place {
    std::uint64_t n;
    int x, y;
    std::uint64_t in_pixel;  ///< n % per_pixel
  };
  Place place(std::uint64_t n) const {
    const std::uint64_t pixel = n / per_pixel;
    const auto width = std::uint64_t(tile.width());
    return {n, tile.x0 + int(pixel % width), tile.y0 + int(pixel / width), n % per_pixel};
  }
  /// place(n), from `last` = place(m) without a division if n is m or m + 1.
  Place place(std::uint64_t n, const Place& last) const {
    if (n == last.n) return last;
    if (n != last.n + 1) return place(n);
    Place next = last;
    next.n = n;
    if (++next.in_pixel < per_pixel) return next;
    next.in_pixel = 0;
    if (++next.x < tile.x1) return next;
    next.x = tile.x0;
    ++next.y;
    return next;
  }

  /// The PixelSamples of samples n[0] .. n[W-1], lane by lane.
  template <int W>
  PixelSamples<W> samples(const std::uint64_t* n, std::uint32_t samples_per_pixel,
                          std::uint64_t seed) const {
    std::uint32_t xs[W], ys[W], indices[W];
    Place at = place(n[0]);
    for (int i = 0; i < W; ++i) {
      at = place(n[i], at);
      xs[i] = std::uint32_t(at.x);
      ys[i] = std::uint32_t(at.y);
      indices[i] = std::uint32_t(std::uint64_t(first) + at.in_pixel);
    }
    return {load<UInt<W>>(xs), load<UInt<W>>(ys), load<UInt<W>>(indices), samples_per_pixel, seed};
  }
};

}  // namespace detail

/// The shading width WavefrontExecution<C> uses: a SIMD register's paths where C's policies
/// have a form for that many lanes, 16 with AVX-512 and 8 with AVX2, else 1. (Sixteen lanes
/// measured 1.00-1.16x the speed of eight on the bench scenes, on a Zen 5 core, for the shading
/// alone: the queries trace as many rays at a time at either width, kQueryRays.)
template <typename C>
consteval int default_shading_width() {
#if defined(GLINT_AVX2) && defined(__AVX512F__)
  if constexpr (PoliciesAtWidth<C, 16>) return 16;
#endif
#if defined(GLINT_AVX2)
  if constexpr (PoliciesAtWidth<C, 8>) return 8;
#endif
  return 1;
}

/// W: the paths shaded at once (1, 8 or 16), default_shading_width by default. Every width
/// gives the same image.
template <RenderConfig C, int W = default_shading_width<C>()>
class WavefrontExecution {
  static_assert(W == 1 || PoliciesAtWidth<C, W>,
                "a policy of this configuration has no form for W lanes");
  static_assert(W == 1 || W == 8 || W == 16);
#if !defined(GLINT_AVX2)
  static_assert(W == 1, "shading several paths at once needs a build with AVX2");
#endif
  static_assert(WavefrontConfig<C>,
                "WavefrontRenderer renders chain configurations only (estimator = PathTracing, "
                "one lobe per bounce); the report's tree follows every lobe at each hit and light "
                "tracing starts at the lights, so use Renderer<C> for them");

 public:
  static constexpr const char* kName = "wavefront";
  using SamplerType = typename C::sampler;
  using Context = PathContext<C>;
  static constexpr bool kSamplesEmitters = Context::kSamplesEmitters;
  /// Paths shaded at once.
  static constexpr int kWidth = W;
  /// Whether the samplers are kept in their Wide form (detail::PathSamplers).
  static constexpr bool kSamplersInLanes = kWidth > 1 && WideSampler<SamplerType, kWidth>;
  /// Whether the camera stage starts kWidth samplers at once (WideSamplerStart).
  static constexpr bool kStartsInLanes = kSamplersInLanes && WideSamplerStart<SamplerType, kWidth>;
  using Lanes = Float<kWidth>;
  using LaneMaskType = Mask<kWidth>;

  /// Paths in flight per thread: enough that the queries' batches stay full while paths end at
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
        estimator_(PathContext<C>(scene, settings.max_depth)),
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
    /// Paths base .. base + kLanesOf<F> - 1.
    template <typename F = Lanes>
    Vec3For<F> load(int base) const {
      const auto u = std::size_t(base);
      return {glint::load<F>(&x_[u]), glint::load<F>(&y_[u]), glint::load<F>(&z_[u])};
    }
    template <typename V3>
    void store(int base, const V3& c) {
      const auto u = std::size_t(base);
      glint::store(&x_[u], c.x);
      glint::store(&y_[u], c.y);
      glint::store(&z_[u], c.z);
    }

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
          from_pdf(kPaths),
          sampler(kPaths),
          shading_throughput(kPaths),
          point_light(kPaths),
          emitter_light(kPaths),
          pending(kPaths),
          ends(kPaths),
          shadow_rays(kShadowQueue / RayBatch::kWidth),
          shadow_owner(kShadowQueue + RayBatch::kWidth),
          shadow_light(kShadowQueue + RayBatch::kWidth),
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
    std::vector<std::uint64_t> sample;     ///< the path's sample, numbered within the tile's work
    detail::AlignedArray<float> from_pdf;  ///< PathLanes::from_pdf
    detail::PathSamplers<SamplerType, kSamplersInLanes ? kWidth : 1> sampler;

    // What the current bounce waits for (PendingLight): light that the queued rays may bring,
    // added by ChainEstimator::add_light once they are traced.
    ColorColumns shading_throughput;  ///< the throughput at the hit
    ColorColumns point_light;         ///< the point lights' light reflected along the path
    ColorColumns emitter_light;
    // A lane of SIMD flags per path: eight paths' flags load and store as one register.
    detail::AlignedArray<std::int32_t> pending;  ///< kDirectLight | kEmitterVisible
    detail::AlignedArray<std::int32_t> ends;     ///< 1: the path ends after this bounce

    // The queues of rays to trace, and for each ray its path and what it brings. The arrays
    // beside the rays have eight entries to spare, which the lane-wise appends write past the
    // last one.
    detail::AlignedArray<RayBatch> shadow_rays;
    std::vector<std::uint32_t> shadow_owner;
    ColorColumns shadow_light;
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
  static constexpr std::int32_t kDirectLight = 1, kEmitterVisible = 2;

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
  /// points of the pixels, as ScalarExecution::add_samples makes them, kWidth at a time.
  GLINT_STAGE void start_paths(ThreadState& state, int first, int last,
                               const PieceLayout& piece) const {
    for (int base = first - first % kWidth; base < last; base += kWidth)
      start_block(state, base, lanes_between(base, first, last), piece);
  }

  /// Paths base .. base + kWidth - 1 of `lanes` start their samples: the samplers at once where
  /// they can be (kStartsInLanes), else one by one; the filter offsets and the camera rays at
  /// the shading width.
  GLINT_FLATTEN void start_block(ThreadState& state, int base, LaneMaskType lanes,
                                 const PieceLayout& piece) const {
    Vec2For<Lanes> film{};
    if constexpr (kStartsInLanes) {
      const PixelSamples<kWidth> sample =
          piece.samples<kWidth>(&state.sample[std::size_t(base)],
                                std::uint32_t(settings_.samples_per_pixel), settings_.seed);
      state.sampler.block(base).start(lanes, sample);
      // The pixel's centre, float(x) + 0.5f, as for one path.
      film = {to_float(std::bit_cast<IntFor<Lanes>>(sample.x)) + 0.5f,
              to_float(std::bit_cast<IntFor<Lanes>>(sample.y)) + 0.5f};
    } else {
      for (int i = 0; i < kWidth; ++i)
        if (lane(lanes, i)) {
          const std::uint64_t n = state.sample[std::size_t(base + i)];
          const int x = piece.x(n);
          const int y = piece.y(n);
          SamplerType sampler;
          sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), piece.index(n),
                                    std::uint32_t(settings_.samples_per_pixel), settings_.seed});
          state.sampler.set(base + i, sampler);
          set_lane(film.x, i, float(x) + 0.5f);
          set_lane(film.y, i, float(y) + 0.5f);
        }
    }
    if constexpr (C::antialiasing::enabled) {
      auto&& draws = draws_of(state, base);
      const Vec2For<Lanes> offset =
          C::antialiasing::offset(next_2d(draws, lanes), settings_.antialias_sigma);
      film.x = film.x + offset.x;
      film.y = film.y + offset.y;
    }
    PathLanes<Lanes> path;
    if (camera_.has_lens()) {
      // The lens point after the filter's offset, as ScalarExecution draws them.
      auto&& draws = draws_of(state, base);
      camera_.rays_through(film, next_2d(draws, lanes), path.ray.origin, path.ray.direction,
                           path.ray.t_min);
    } else {
      path.ray.origin = splat_vector<Vec3For<Lanes>>(camera_.position());
      camera_.rays_through(film, path.ray.direction, path.ray.t_min);
    }
    path.ray.t_max = splat<Lanes>(kInfinity);
    path.ray.origin_sphere = splat<UIntFor<Lanes>>(kNoSphere);
    path.ray.heads_into_origin_sphere = mask_of<LaneMaskType>(false);
    path.throughput = splat_vector<Vec3For<Lanes>>(Color(1.0f));
    path.radiance = splat_vector<Vec3For<Lanes>>(Color(0.0f));
    path.depth = splat<IntFor<Lanes>>(0);
    path.from_pdf = splat<Lanes>(0.0f);
    store_paths(state, base, lanes, path);
  }

  /// The lanes of block `base` that hold paths first .. last-1.
  static LaneMaskType lanes_between(int base, int first, int last) {
    // Lanes i with first <= base + i < last, as bits, each bound clamped to 0 .. kWidth.
    const auto below = [](int lanes) {
      return (std::uint64_t(1) << std::clamp(lanes, 0, kWidth)) - 1;
    };
    return mask_of_bits<LaneMaskType>(std::uint32_t(below(last - base) & ~below(first - base)));
  }

  /// kWidth consecutive values of a column of the 8-lane blocks `blocks` from path `base` on
  /// (two blocks' columns for 16 paths), and back.
  template <typename T, typename Block, typename S>
  static T load_column(const Block* blocks, S (Block::*column)[RayBatch::kWidth], int base) {
    const Block& block = blocks[base / RayBatch::kWidth];
    if constexpr (kWidth <= RayBatch::kWidth) {
      return load<T>(&(block.*column)[base % RayBatch::kWidth]);
    } else {
      using Half = decltype(low_half(T{}));
      return join(load<Half>(block.*column), load<Half>((&block + 1)->*column));
    }
  }
  template <typename Block, typename S, typename T>
  static void store_column(Block* blocks, S (Block::*column)[RayBatch::kWidth], int base,
                           LaneMaskType lanes, T value) {
    value = select(lanes, value, load_column<T>(blocks, column, base));
    Block& block = blocks[base / RayBatch::kWidth];
    if constexpr (kWidth <= RayBatch::kWidth) {
      store(&(block.*column)[base % RayBatch::kWidth], value);
    } else {
      store(block.*column, low_half(value));
      store((&block + 1)->*column, high_half(value));
    }
  }
  /// The heads_into_origin_sphere bits of paths base .. base + kWidth - 1, and back.
  static LaneMask heads_into_bits(const RayBatch* blocks, int base) {
    const RayBatch& block = blocks[base / RayBatch::kWidth];
    if constexpr (kWidth <= RayBatch::kWidth)
      return block.heads_into_origin_sphere >> (base % RayBatch::kWidth);
    else
      return block.heads_into_origin_sphere | (&block + 1)->heads_into_origin_sphere
                                                  << RayBatch::kWidth;
  }
  static void set_heads_into_bits(RayBatch* blocks, int base, LaneMask lanes, LaneMask bits) {
    for (int half = 0; half < std::max(1, kWidth / RayBatch::kWidth); ++half) {
      RayBatch& block = blocks[base / RayBatch::kWidth + half];
      const int shift = kWidth <= RayBatch::kWidth ? base % RayBatch::kWidth : 0;
      const LaneMask in = ((lanes >> (RayBatch::kWidth * half)) & RayBatch::kAllLanes) << shift;
      const LaneMask to = ((bits >> (RayBatch::kWidth * half)) & RayBatch::kAllLanes) << shift;
      block.heads_into_origin_sphere = (block.heads_into_origin_sphere & ~in) | (to & in);
    }
  }

  /// The state of paths base .. base + kWidth - 1 between bounces.
  static PathLanes<Lanes> load_paths(const ThreadState& state, int base) {
    using U = UIntFor<Lanes>;
    const RayBatch* rays = state.rays.data();
    PathLanes<Lanes> path;
    path.ray.origin = {load_column<Lanes>(rays, &RayBatch::origin_x, base),
                       load_column<Lanes>(rays, &RayBatch::origin_y, base),
                       load_column<Lanes>(rays, &RayBatch::origin_z, base)};
    path.ray.direction = {load_column<Lanes>(rays, &RayBatch::direction_x, base),
                          load_column<Lanes>(rays, &RayBatch::direction_y, base),
                          load_column<Lanes>(rays, &RayBatch::direction_z, base)};
    path.ray.t_min = load_column<Lanes>(rays, &RayBatch::t_min, base);
    path.ray.t_max = load_column<Lanes>(rays, &RayBatch::t_max, base);
    path.ray.origin_sphere = load_column<U>(rays, &RayBatch::origin_sphere, base);
    path.ray.heads_into_origin_sphere = mask_of_bits<LaneMaskType>(heads_into_bits(rays, base));
    path.throughput = state.throughput.load(base);
    path.radiance = state.radiance.load(base);
    path.depth = load<IntFor<Lanes>>(&state.depth[std::size_t(base)]);
    path.from_pdf = load<Lanes>(&state.from_pdf[std::size_t(base)]);
    return path;
  }

  /// Stores the lanes of `lanes` of `path` as paths base .. base + kWidth - 1.
  static void store_paths(ThreadState& state, int base, LaneMaskType lanes,
                          const PathLanes<Lanes>& path) {
    RayBatch* rays = state.rays.data();
    store_column(rays, &RayBatch::origin_x, base, lanes, path.ray.origin.x);
    store_column(rays, &RayBatch::origin_y, base, lanes, path.ray.origin.y);
    store_column(rays, &RayBatch::origin_z, base, lanes, path.ray.origin.z);
    store_column(rays, &RayBatch::direction_x, base, lanes, path.ray.direction.x);
    store_column(rays, &RayBatch::direction_y, base, lanes, path.ray.direction.y);
    store_column(rays, &RayBatch::direction_z, base, lanes, path.ray.direction.z);
    store_column(rays, &RayBatch::t_min, base, lanes, path.ray.t_min);
    store_column(rays, &RayBatch::t_max, base, lanes, path.ray.t_max);
    store_column(rays, &RayBatch::origin_sphere, base, lanes, path.ray.origin_sphere);
    set_heads_into_bits(rays, base, bits_of_mask(lanes),
                        bits_of_mask(path.ray.heads_into_origin_sphere));
    state.throughput.store(base, select(lanes, path.throughput, state.throughput.load(base)));
    state.radiance.store(base, select(lanes, path.radiance, state.radiance.load(base)));
    const auto update = [&](auto* column, auto value) {
      store(column, select(lanes, value, load<decltype(value)>(column)));
    };
    update(&state.depth[std::size_t(base)], path.depth);
    update(&state.from_pdf[std::size_t(base)], path.from_pdf);
  }

  GLINT_STAGE void trace_closest_hits(ThreadState& state, int live, TraceCounters& counters) const {
    counters.rays += std::uint64_t(live);
    for_each_query(live, [&](std::size_t block, LaneMask lanes, bool pair) {
      if (pair)
        scene_.closest_hits(std::span<const RayBatch, 2>(&state.rays[block], 2), lanes,
                            std::span<HitBatch, 2>(&state.hits[block], 2));
      else
        scene_.closest_hits(state.rays[block], lanes, state.hits[block]);
    });
  }

  /// Rays that one batched query traces: two batches' with AVX-512, whose kernels take sixteen
  /// lanes at once (Scene::closest_hits for two batches), else one batch's.
#if defined(GLINT_AVX512)
  static constexpr int kQueryRays = 2 * RayBatch::kWidth;
#else
  static constexpr int kQueryRays = RayBatch::kWidth;
#endif

  /// Calls query(first batch, lanes, pair) for the first `count` rays of a queue of RayBatches,
  /// kQueryRays at a time: the rays of batch `first` (and of the next one where `pair`, its lanes
  /// in bits 8-15) of the mask `lanes`.
  template <typename Query>
  static void for_each_query(int count, Query&& query) {
    for (int base = 0; base < count; base += kQueryRays) {
      const int rays = std::min(kQueryRays, count - base);
      query(std::size_t(base / RayBatch::kWidth), LaneMask((std::uint64_t(1) << rays) - 1),
            rays > RayBatch::kWidth);
    }
  }

  GLINT_STAGE void shade(ThreadState& state, int live, TraceCounters& counters) const {
    for (int base = 0; base < live; base += kWidth)
      shade_block(state, base, lanes_between(base, 0, live), counters);
  }

  /// ChainEstimator::step for paths base .. base + kWidth - 1 of `lanes` at the hits their
  /// rays found, its light rays queued: their light is added by gather_and_retire.
  GLINT_FLATTEN void shade_block(ThreadState& state, int base, LaneMaskType lanes,
                                 TraceCounters& counters) const {
    const HitBatch* hits = state.hits.data();
    PathLanes<Lanes> path = load_paths(state, base);
    PendingLight<Lanes> pending{};
    LightQueue queue{*this, state, base};
    auto&& draws = draws_of(state, base);
    const LaneMaskType going_on =
        estimator_.step(lanes, path, load_column<Lanes>(hits, &HitBatch::t, base),
                        load_column<UIntFor<Lanes>>(hits, &HitBatch::sphere, base), draws, queue,
                        pending, counters);
    store_paths(state, base, lanes, path);
    using I = IntFor<Lanes>;
    const auto u = std::size_t(base);
    store(&state.pending[u], select(pending.direct, splat<I>(kDirectLight), splat<I>(0)));
    store(&state.ends[u], select(going_on, splat<I>(0), splat<I>(1)));
    state.shading_throughput.store(base, pending.throughput);
    state.point_light.store(base, splat_vector<Vec3For<Lanes>>(Color(0.0f)));
  }

  /// Where ChainEstimator::step's light rays go for paths base .. base + kWidth - 1: the
  /// thread's queues, traced by trace_shadow_rays and trace_emitter_rays.
  class LightQueue {
   public:
    LightQueue(const WavefrontExecution& execution, ThreadState& state, int base)
        : execution_(execution), state_(state), base_(base) {}

    void shadow_rays(LaneMaskType lit, const RayFor<Lanes>& rays, const Vec3For<Lanes>& light) {
      if constexpr (kWidth == 1) {
        if (lit) execution_.queue_shadow_ray(state_, base_, rays, light);
      } else {
        for_each_block(bits_of_mask(lit), rays, [&](int at, LaneMask bits, const auto& block) {
          execution_.queue_shadow_rays(state_, base_ + at, bits, block, eight_lanes(light, at));
        });
      }
    }
    void emitter_rays(LaneMaskType sampled, const RayFor<Lanes>& rays,
                      UIntFor<Lanes> emitter_sphere, const Vec3For<Lanes>& light) {
      state_.emitter_light.store(base_, select(sampled, light, state_.emitter_light.load(base_)));
      if constexpr (kWidth == 1) {
        if (sampled) queue_emitter_ray(state_, base_, rays, emitter_sphere);
      } else {
        for_each_block(bits_of_mask(sampled), rays, [&](int at, LaneMask bits, const auto& block) {
          queue_emitter_rays(state_, base_ + at, bits, block, eight_lanes(emitter_sphere, at));
        });
      }
    }

   private:
    /// visit(first lane, lane bits, rays) for each 8-lane block of `rays` with lanes in `bits`,
    /// in lane order (the queues append eight lanes at a time).
    template <typename Visit>
    static void for_each_block(LaneMask bits, const RayFor<Lanes>& rays, Visit&& visit) {
      for (int at = 0; at < kWidth; at += RayBatch::kWidth) {
        const LaneMask block_bits = (bits >> at) & RayBatch::kAllLanes;
        if (block_bits == 0) continue;
        visit(at, block_bits,
              RayLanes<Float<RayBatch::kWidth>>{
                  eight_lanes(rays.origin, at), eight_lanes(rays.direction, at),
                  eight_lanes(rays.t_min, at), eight_lanes(rays.t_max, at),
                  eight_lanes(rays.origin_sphere, at),
                  eight_lanes(rays.heads_into_origin_sphere, at)});
      }
    }
    /// Lanes at .. at + 7 of a value of kWidth (8 or 16) lanes.
    template <typename T>
    static auto eight_lanes(const T& value, int at) {
      if constexpr (std::is_same_v<T, Vec3For<Lanes>>) {
        return Vector3<Float<RayBatch::kWidth>>{eight_lanes(value.x, at), eight_lanes(value.y, at),
                                                eight_lanes(value.z, at)};
      } else if constexpr (kLanesOf<T> == RayBatch::kWidth) {
        return value;
      } else {
        return at == 0 ? low_half(value) : high_half(value);
      }
    }

   private:
    const WavefrontExecution& execution_;
    ThreadState& state_;
    int base_;
  };

  /// The samplers of paths base .. base + kWidth - 1, to draw from with next_1d(draws, mask)
  /// and next_2d(draws, mask): path base's own sampler at width 1; wider, their Lanes form in
  /// place (kSamplersInLanes), else a SamplerBlock that draws lane by lane.
  static decltype(auto) draws_of(ThreadState& state, int base) {
    if constexpr (kWidth == 1)
      return state.sampler[base];
    else if constexpr (kSamplersInLanes)
      return state.sampler.block(base);
    else
      return SamplerBlock(state.sampler, base);
  }

  /// The samplers of paths base .. base + kWidth - 1 drawn from one by one, for a sampler
  /// without a Wide form. Each draw is for the lanes of a mask, whose samplers alone advance;
  /// the values of the other lanes are unspecified.
  class SamplerBlock {
   public:
    SamplerBlock(detail::PathSamplers<SamplerType, 1>& samplers, int base)
        : samplers_(samplers), base_(base) {}

    Lanes next_1d(LaneMaskType mask) {
      Lanes value = splat<Lanes>(0.0f);
      for (int i = 0; i < kWidth; ++i)
        if (lane(mask, i)) set_lane(value, i, samplers_[base_ + i].next_1d());
      return value;
    }
    Vec2For<Lanes> next_2d(LaneMaskType mask) {
      Vec2For<Lanes> value{splat<Lanes>(0.0f), splat<Lanes>(0.0f)};
      for (int i = 0; i < kWidth; ++i)
        if (lane(mask, i)) {
          const Vec2 u = samplers_[base_ + i].next_2d();
          set_lane(value.x, i, u.x);
          set_lane(value.y, i, u.y);
        }
      return value;
    }

   private:
    detail::PathSamplers<SamplerType, 1>& samplers_;
    int base_;
  };

#if defined(GLINT_AVX2)
  /// Appends the rays of lanes `lanes` of `rays` to the queue `blocks`, which holds `count`
  /// rays, in lane order: what RayBatch::set would write lane by lane, a column at a time. The
  /// queue has room for them.
  static void append_rays(RayBatch* blocks, int count, LaneMask lanes, IntLanes packing,
                          const RayLanes<FloatLanes>& rays) {
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
      store(last.*column, select(into_last, value, load<FloatLanes>(last.*column)));
      if (next) store(next->*column, select(into_next, value, load<FloatLanes>(next->*column)));
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
    const IntLanes origin_sphere = permute(std::bit_cast<IntLanes>(rays.origin_sphere), order);
    append_ids(last, into_last, origin_sphere);
    if (next) append_ids(*next, into_next, origin_sphere);
    const LaneMask heads_in = bits_of_mask(permute(rays.heads_into_origin_sphere, order));
    const auto merge = [&](RayBatch& batch, IntLanes into) {
      const LaneMask bits = bits_of_mask(into);
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
  void queue_shadow_rays(ThreadState& state, int base, LaneMask lanes,
                         const RayLanes<FloatLanes>& rays, const Vec3Lanes& light) const {
    if (state.shadow_count + std::popcount(lanes) > kShadowQueue) trace_shadow_rays(state);
    const int q = state.shadow_count;
    const IntLanes packing = packing_order(lanes);
    append_rays(state.shadow_rays.data(), q, lanes, packing, rays);
    append_values(&state.shadow_owner[std::size_t(q)], packing, base + lane_indices());
    state.shadow_light.store(q, Vec3Lanes{permute(light.x, packing), permute(light.y, packing),
                                          permute(light.z, packing)});
    state.shadow_count += std::popcount(lanes);
  }

  /// queue_emitter_ray for the lanes of `lanes` of paths base .. base+7, in lane order.
  static void queue_emitter_rays(ThreadState& state, int base, LaneMask lanes,
                                 const RayLanes<FloatLanes>& rays, UintLanes emitter_sphere) {
    const int q = state.emitter_count;
    const IntLanes packing = packing_order(lanes);
    append_rays(state.emitter_rays.data(), q, lanes, packing, rays);
    append_values(&state.emitter_owner[std::size_t(q)], packing, base + lane_indices());
    append_values(&state.emitter_sphere[std::size_t(q)], packing,
                  std::bit_cast<IntLanes>(emitter_sphere));
    state.emitter_count += std::popcount(lanes);
  }

#endif  // GLINT_AVX2

  void queue_shadow_ray(ThreadState& state, int p, const Ray& ray, const Color& light) const {
    if (state.shadow_count == kShadowQueue) trace_shadow_rays(state);
    const int q = state.shadow_count++;
    state.shadow_rays[std::size_t(q / RayBatch::kWidth)].set(q % RayBatch::kWidth, ray);
    state.shadow_owner[std::size_t(q)] = std::uint32_t(p);
    state.shadow_light.set(q, light);
  }

  static void queue_emitter_ray(ThreadState& state, int p, const Ray& ray, std::uint32_t sphere) {
    const int q = state.emitter_count++;
    state.emitter_rays[std::size_t(q / RayBatch::kWidth)].set(q % RayBatch::kWidth, ray);
    state.emitter_owner[std::size_t(q)] = std::uint32_t(p);
    state.emitter_sphere[std::size_t(q)] = sphere;
  }

  /// Traces the queued shadow rays and adds the light of those not blocked to their paths'
  /// point_light, in the order they were queued (a path's lights in the scene's order).
  GLINT_STAGE void trace_shadow_rays(ThreadState& state) const {
    for_each_query(state.shadow_count, [&](std::size_t block, LaneMask lanes, bool pair) {
      const LaneMask blocked =
          pair ? scene_.occluded(std::span<const RayBatch, 2>(&state.shadow_rays[block], 2), lanes)
               : scene_.occluded(state.shadow_rays[block], lanes);
      for_each_lane(lanes & ~blocked, [&](int lane) {
        const std::size_t q = block * RayBatch::kWidth + std::size_t(lane);
        const auto owner = int(state.shadow_owner[q]);
        state.point_light.set(owner, state.point_light.get(owner) + state.shadow_light.get(int(q)));
      });
    });
    state.shadow_count = 0;
  }

  /// Traces the queued emitter rays: the light arrives where the first sphere hit is the
  /// emitter (PathContext::sample_emitter's test).
  GLINT_STAGE void trace_emitter_rays(ThreadState& state) const {
    for_each_query(state.emitter_count, [&](std::size_t block, LaneMask lanes, bool pair) {
      HitBatch found[2];
      if (pair)
        scene_.closest_hits(std::span<const RayBatch, 2>(&state.emitter_rays[block], 2), lanes,
                            std::span<HitBatch, 2>(found));
      else
        scene_.closest_hits(state.emitter_rays[block], lanes, found[0]);
      for (int half = 0; half < (pair ? 2 : 1); ++half) {
        const std::size_t first = (block + std::size_t(half)) * RayBatch::kWidth;
        const LaneMask active = (lanes >> (RayBatch::kWidth * half)) & RayBatch::kAllLanes;
        LaneMask visible = 0;
#if defined(GLINT_AVX2)
        IntLanes found_sphere, emitter_sphere;
        std::memcpy(&found_sphere, found[half].sphere, sizeof found_sphere);
        std::memcpy(&emitter_sphere, &state.emitter_sphere[first], sizeof emitter_sphere);
        visible = active & bits_of_mask(found_sphere == emitter_sphere);
#else
        for_each_lane(active, [&](int lane) {
          if (found[half].sphere[lane] == state.emitter_sphere[first + std::size_t(lane)])
            visible |= LaneMask(1) << lane;
        });
#endif
        for_each_lane(visible, [&](int lane) {
          state.pending[state.emitter_owner[first + std::size_t(lane)]] |= kEmitterVisible;
        });
      }
    });
    state.emitter_count = 0;
  }

  /// Adds the light the traced rays found to each path (ChainEstimator::add_light) and retires
  /// the paths that ended, their radiance kept for add_finished; the paths that go on are
  /// moved down to fill the holes. Returns the number left.
  GLINT_STAGE static int gather_and_retire(ThreadState& state, int live) {
    for (int base = 0; base < live; base += kWidth)
      gather_block(state, base);
    // The ended paths as bits, visited from the last down: a path moved into a hole comes from
    // above it, where every path has been visited, so the bits taken first stay true. (A test of
    // each path's flag instead is a branch that mispredicts about once per ended path.)
    std::uint64_t ended[kPaths / 64] = {};
    for (int base = 0; base < live; base += RayBatch::kWidth) {
      std::uint64_t bits = 0;
#if defined(GLINT_AVX2)
      bits = bits_of_mask(load<IntLanes>(&state.ends[std::size_t(base)]) != 0);
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

  /// add_light for paths base .. base + kWidth - 1 (those beyond the live ones are left as
  /// they are: their pending flags are clear).
  static void gather_block(ThreadState& state, int base) {
    using I = IntFor<Lanes>;
    const I pending = load<I>(&state.pending[std::size_t(base)]);
    const LaneMaskType direct = (pending & kDirectLight) != 0;
    const LaneMaskType visible = (pending & kEmitterVisible) != 0;
    if (!any(direct || visible)) return;
    state.radiance.store(
        base, ChainEstimator<C>::add_light(
                  state.radiance.load(base),
                  PendingLight<Lanes>{direct, state.shading_throughput.load(base)},
                  state.point_light.load(base), visible, state.emitter_light.load(base)));
  }

  /// Moves path `from` (still going on) to place `to`, whose path has ended.
  static void move_path(ThreadState& state, int from, int to) {
    const auto f = std::size_t(from), t = std::size_t(to);
    set_ray(state, to, ray_of(state, from));
    state.throughput.set(to, state.throughput.get(from));
    state.radiance.set(to, state.radiance.get(from));
    state.depth[t] = state.depth[f];
    state.sample[t] = state.sample[f];
    state.from_pdf[t] = state.from_pdf[f];
    state.sampler.move(from, to);
  }

  /// Adds the finished samples from `summed` on, in order, to their pixels' sums, up to the
  /// first one still in flight; returns where it stopped. A sample that is not finite is
  /// counted as invalid instead (ScalarExecution::add_samples's rule).
  GLINT_STAGE static std::uint64_t add_finished(ThreadState& state, const PieceLayout& piece,
                                                std::uint64_t summed, std::uint64_t started,
                                                PixelSums& sums, TraceCounters& counters) {
    if (summed >= started) return summed;
    PieceLayout::Place at = piece.place(summed);
    for (; summed < started; ++summed) {
      const auto slot = std::size_t(summed % std::uint64_t(kWindow));
      if (!state.result_ready[slot]) break;
      state.result_ready[slot] = 0;
      at = piece.place(summed, at);
      const Color& sample = state.results[slot];
      if (std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z))
        sums.at(at.x, at.y) += ColorSum(sample);
      else
        ++counters.invalid_samples;
    }
    return summed;
  }

  const Scene& scene_;
  ChainEstimator<C> estimator_;
  Camera camera_;
  RenderSettings settings_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE

#undef GLINT_FLATTEN
#undef GLINT_STAGE
