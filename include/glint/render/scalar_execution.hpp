#pragma once
// How a renderer's threads turn a tile's samples into pixel sums: the execution model. A
// Renderer (render/renderer.hpp) schedules tiles and passes; its execution renders one piece of
// work (samples [first, last) of every pixel of a tile) into the pixels' sums. Two models share
// that contract: ScalarExecution here, one path at a time through PathTracer, and
// WavefrontExecution (render/wavefront/), many paths advanced together stage by stage.

#include <atomic>
#include <cmath>
#include <concepts>
#include <cstdint>

#include "glint/config.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/path_tracer.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// An execution model. Built once per render from the scene and the settings (both outlive it)
/// and shared read-only by the threads; each thread owns a ThreadState (its scratch memory,
/// built from the execution) and calls render_tile for each piece of work it takes: add samples
/// [first, last) of every pixel of `tile` to the pixels' sums in sample index order, count rays
/// and invalid samples in `counters`, count the samples in `samples` and publish that count in
/// `progress` (relaxed). A pixel's sum must depend only on the scene, the settings and the
/// samples, never on the thread or on which other pieces the thread rendered.
template <class E>
concept Execution = requires(const E& execution, typename E::ThreadState& state, const Tile& tile,
                             int first, int last, PixelSums& sums, TraceCounters& counters,
                             std::atomic<std::uint64_t>& progress, std::uint64_t& samples) {
  requires std::constructible_from<E, const Scene&, const RenderSettings&>;
  requires std::constructible_from<typename E::ThreadState, const E&>;
  execution.render_tile(state, tile, first, last, sums, counters, progress, samples);
};

/// One path at a time, pixel by pixel: PathTracer<C> over each sample in index order.
template <typename C>
class ScalarExecution {
  static_assert(RenderConfig<C>);

 public:
  static constexpr const char* kName = "scalar";

  ScalarExecution(const Scene& scene, const RenderSettings& settings)
      : camera_(scene.camera(), settings.width, settings.height),
        tracer_(scene, settings.max_depth),
        settings_(settings) {}

  /// Nothing: a path lives on the stack.
  struct ThreadState {
    explicit ThreadState(const ScalarExecution&) {}
  };

  void render_tile(ThreadState&, const Tile& tile, int first, int last, PixelSums& sums,
                   TraceCounters& counters, std::atomic<std::uint64_t>& progress,
                   std::uint64_t& samples) const {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        sums.at(x, y) = add_samples(tracer_, camera_, settings_, x, y, first, last, sums.at(x, y),
                                    counters, progress, samples);
  }

  /// The mean of the first `samples` samples of pixel (x, y) of a render with these settings,
  /// summed in one go: what a render stopped when `samples` samples per pixel were done holds,
  /// bit for bit. Exposed for tests.
  static Color render_pixel(const PathTracer<C>& tracer, const Camera& camera,
                            const RenderSettings& settings, int x, int y, TraceCounters& counters,
                            int samples);

  /// `sum` plus samples [first, last) of pixel (x, y), in index order; a sample that is not
  /// finite is counted as invalid instead. `samples` counts them, published in `progress`. The one
  /// definition of a pixel's sum, shared by render and render_pixel so that both give the same
  /// bits. Kept out of line, and out of interprocedural optimisation, so that a program holds one
  /// copy of it: with -ffp-contract=off all copies agree, but a program built without it (see
  /// glint/fp_contract.hpp) may fuse each copy's multiplies and adds differently, and render and
  /// render_pixel would disagree by a few ulps. A call per pixel and pass costs nothing here.
#if defined(__GNUC__) && !defined(__clang__)
  [[gnu::noipa]]
#else
  [[gnu::noinline]]
#endif
  static ColorSum
  add_samples(const PathTracer<C>& tracer, const Camera& camera, const RenderSettings& settings,
              int x, int y, int first, int last, ColorSum sum, TraceCounters& counters,
              std::atomic<std::uint64_t>& progress, std::uint64_t& samples) {
    typename C::sampler sampler;
    for (int s = first; s < last; ++s) {
      sampler.start(PixelSample{std::uint32_t(x), std::uint32_t(y), std::uint32_t(s),
                                std::uint32_t(settings.samples_per_pixel), settings.seed});
      Vec2 film(float(x) + 0.5f, float(y) + 0.5f);
      if constexpr (C::antialiasing::enabled)
        film += C::antialiasing::offset(sampler.next_2d(), settings.antialias_sigma);
      const Color sample = tracer.radiance(camera.sample_ray(film, sampler), sampler, counters);
      if (std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z))
        sum += ColorSum(sample);
      else
        ++counters.invalid_samples;
    }
    // Once per call: a store per sample kept the compiler from optimising across samples
    // (about 1% more instructions, callgrind).
    samples += std::uint64_t(last - first);
    progress.store(samples, std::memory_order_relaxed);
    return sum;
  }

 private:
  Camera camera_;
  PathTracer<C> tracer_;
  RenderSettings settings_;
};

// Out of the class, so that an explicit instantiation declaration of ScalarExecution<C> keeps
// other translation units from compiling it (see Renderer::render).
template <typename C>
Color ScalarExecution<C>::render_pixel(const PathTracer<C>& tracer, const Camera& camera,
                                       const RenderSettings& settings, int x, int y,
                                       TraceCounters& counters, int samples) {
  std::atomic<std::uint64_t> progress{0};
  std::uint64_t done = 0;
  const ColorSum sum = add_samples(tracer, camera, settings, x, y, 0, samples, ColorSum(0.0),
                                   counters, progress, done);
  bool out_of_range = false;
  return mean_color(sum, samples, out_of_range);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
