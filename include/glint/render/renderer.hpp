#pragma once
// Renderer<Config>: renders a Scene into a Film on every core, in passes of samples.
//
// A render is a sequence of passes (pass_ends in render_settings.hpp): each pass adds the
// next samples of every pixel to that pixel's running sum, so after every pass the sums hold
// a complete image of k samples per pixel, and a render can stop there. A pixel's samples are
// added in index order into one double sum (image/pixel_sums.hpp) that lives between passes,
// then divided once by their count: exactly ScalarExecution::render_pixel's arithmetic, so the
// finished image does not depend on the passes. Within a pass, square tiles are handed out by one
// atomic counter; each tile's pixels are written by the one thread that took it, and every sample's
// randomness comes from hashing (pixel, sample index, seed). So the image is the same bit for
// bit whatever the thread count or scheduling. The hot loop has no locks, no allocation, no
// virtual calls and no exceptions; threads meet only between passes. How a thread renders a
// tile's samples is the execution model's (render/scalar_execution.hpp): one path at a time by
// default, or a wavefront of paths (WavefrontRenderer).
//
// render_tiles is the same loop over work handed out by the caller (tile by tile, from any
// schedule: glint-render-mpi's, across processes), for renders that are scheduled elsewhere.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <concepts>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "glint/config.hpp"
#include "glint/error.hpp"
#include "glint/image/film.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/bidirectional_execution.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/path_tracer.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/scalar_execution.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/render/work_estimate.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Whether execution model E splats (adds light to pixels other than the one it renders, as a
/// light tracer does): the sums it renders into then carry a splat layer.
template <class E>
inline constexpr bool kExecutionSplats = requires {
  requires E::kSplats;
};

/// Whether execution model E begins each sample index with a light phase shared by every pixel
/// (E::prepare_sample, as vertex merging's light paths): it is then rendered one sample index
/// at a time, each index's tiles after its light phase.
template <class E>
inline constexpr bool kExecutionHasLightPhase = requires {
  requires E::kLightPhase;
};

struct RenderResult {
  /// The mean of the samples of the completed passes; black when no pass completed.
  Film film;
  RenderStats stats;
  int samples_per_pixel = 0;  ///< samples in every pixel of `film`
  int passes_done = 0;
  int pass_count = 0;  ///< passes planned for the requested samples per pixel
  /// The per-pixel sums of the completed passes' samples (what a checkpoint keeps), when
  /// RenderControl::keep_sums asked for them; empty otherwise.
  PixelSums sums;
  /// Whether every requested sample is in the image (no stop request cut the render short).
  bool complete() const { return passes_done == pass_count; }
};

/// A pass has completed: the sums of `samples_per_pixel` samples in every pixel are ready.
struct PassReport {
  int passes_done = 0;
  int pass_count = 0;
  int samples_per_pixel = 0;
  double elapsed_seconds = 0.0;
  const PixelSums& sums;  ///< per-pixel sums of the samples so far; valid during the callback only
  /// The image so far, bit for bit what a render stopped after this pass returns.
  Film image() const;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;
/// Called after every pass; returning false stops the render there.
using PassCallback = std::function<bool(const PassReport&)>;

/// Where a render begins. Default: from black, at the first pass. With `sums` set: after pass
/// `passes_done`, from the per-pixel sums a render with the same settings had then (a
/// PassReport's sums, as a checkpoint keeps them). The remaining passes add to those sums, so
/// the image ends bit for bit as an uninterrupted render's, whatever the thread counts of
/// either; the callbacks see only the remaining passes.
struct RenderStart {
  const PixelSums* sums =
      nullptr;          ///< width x height of the settings; read, and copied, at the start
  int passes_done = 0;  ///< between 0 and the pass count; 0 without sums
};

/// How a caller follows and stops a render. Every callback runs on the calling thread, never
/// on a worker, while the workers wait or render; the render stops only between passes.
struct RenderControl {
  ProgressCallback progress;
  PassCallback pass_done;
  /// Checked before each pass, the first included: once true, the render returns the image of
  /// the passes completed so far. A lock-free atomic, so a signal handler may set it.
  const std::atomic<bool>* stop = nullptr;
  /// Keep the sums in RenderResult::sums: a caller that saves them after the render (a
  /// checkpoint) then needs no copy of its own, 24 bytes a pixel.
  bool keep_sums = false;
};

/// Samples [first_sample, last_sample) of every pixel of tile `tile` (of TileGrid(settings)),
/// to be added to the pixels' sums.
struct TileWork {
  std::size_t tile = 0;
  int first_sample = 0;
  int last_sample = 0;
  std::uint64_t id = 0;  ///< the work source's own, given back to its finished() unchanged
};

/// Where Renderer::render_tiles's threads get their work. next() hands out the next piece, and
/// may block until there is one; it returns nullopt once there is none left, to each thread in
/// turn (the thread then ends). finished() says a piece is done: its sums are written. Both are
/// called from every rendering thread at once, so they must be thread-safe, and they must not
/// throw. For the image to be bit for bit a render's, a pixel's samples must be added in index
/// order: a tile's samples [a, b) are handed out only after those before `a` have finished,
/// into the sums they left.
template <typename S>
concept TileWorkSource = requires(S& source, const TileWork& work) {
  { source.next() } -> std::same_as<std::optional<TileWork>>;
  source.finished(work);
};

/// Any TileWorkSource, by reference: what the compiled form of render_tiles takes, so that one
/// instantiation of a renderer serves every source. Its calls are one per tile, not per sample.
class TileWorkSourceRef {
 public:
  template <TileWorkSource S>
  requires(!std::same_as<S, TileWorkSourceRef>) explicit TileWorkSourceRef(S& source)
      : source_(&source),
        next_([](void* s) { return static_cast<S*>(s)->next(); }),
        finished_([](void* s, const TileWork& work) { static_cast<S*>(s)->finished(work); }) {}

  std::optional<TileWork> next() { return next_(source_); }
  void finished(const TileWork& work) { finished_(source_, work); }

 private:
  void* source_;
  std::optional<TileWork> (*next_)(void*);
  void (*finished_)(void*, const TileWork&);
};

inline Film PassReport::image() const {
  return mean_image(sums, samples_per_pixel).film;
}

/// The first sphere whose shading kind variant C's SphereShading policy does not support.
template <RenderConfig C>
std::optional<std::uint32_t> first_unsupported_sphere(const Scene& scene) {
  for (std::uint32_t i = 0; i < scene.sphere_count(); ++i)
    if (!C::sphere_shading::supports(scene.surface(i).shading)) return i;
  return std::nullopt;
}

/// The first sphere whose material variant C's material model does not render.
template <RenderConfig C>
std::optional<std::uint32_t> first_unsupported_material(const Scene& scene) {
  for (std::uint32_t i = 0; i < scene.sphere_count(); ++i)
    if (!C::material_model::supports(scene.surface(i).material)) return i;
  return std::nullopt;
}

/// Throws UnsupportedSceneError, naming the sphere's line, if variant C cannot render the scene:
/// a shading kind its SphereShading policy does not support, a material its material model does
/// not render, or what its estimator's execution model refuses (E::check_supported, where it has
/// one: light tracing's black background).
template <RenderConfig C>
void check_supported(const Scene& scene) {
  using E = typename C::estimator::template execution<C>;
  if constexpr (requires { E::check_supported(scene); }) E::check_supported(scene);
  if (const std::optional<std::uint32_t> sphere = first_unsupported_sphere<C>(scene))
    throw UnsupportedSceneError(scene.source(), scene.sphere_line(*sphere),
                                "shading '" +
                                    std::string(to_string(scene.surface(*sphere).shading)) +
                                    "' is not supported by this renderer variant");
  if (const std::optional<std::uint32_t> sphere = first_unsupported_material<C>(scene))
    throw UnsupportedSceneError(
        scene.source(), scene.sphere_line(*sphere),
        "a rough or metal mirror or rough glass (mirror_roughness, metal, transparent_roughness) "
        "is not supported by this renderer variant's material model (" +
            std::string(C::material_model::name) + ")");
}

/// Whether variant C can render the scene (check_supported would not throw).
template <RenderConfig C>
bool is_supported(const Scene& scene) {
  try {
    check_supported<C>(scene);
    return true;
  } catch (const UnsupportedSceneError&) {
    return false;
  }
}

/// Renders scenes with the policies of Config C, each piece of work (a tile's samples) done by
/// execution model E: ScalarExecution<C>, one path at a time, by default; WavefrontRenderer
/// (render/wavefront/wavefront_renderer.hpp) is this renderer with WavefrontExecution<C>.
template <RenderConfig C, Execution E = typename C::estimator::template execution<C>>
class Renderer {
 public:
  using Config = C;
  using ExecutionModel = E;

  /// The longest the progress callback waits while rendering: progress and the time left keep
  /// moving on scenes where a tile, or a single sample, takes longer.
  static constexpr std::chrono::milliseconds progress_interval{100};

  /// Renders with the given settings; `progress`, if set, is called from the calling thread
  /// (never from a worker). Throws SettingsError for settings outside the limits or work
  /// beyond limits::max_tree_rays_per_sample (check_work), UnsupportedSceneError for a scene this
  /// variant cannot render, and Error when the worker threads cannot be started (before any
  /// rendering).
  static RenderResult render(const Scene& scene, const RenderSettings& settings,
                             const ProgressCallback& progress = {}) {
    return render(scene, settings, RenderControl{progress, {}, nullptr});
  }

  /// Renders pass by pass under `control`: progress reports, a callback after each pass, and
  /// a stop request honoured between passes; `from` may begin it after some passes (resuming a
  /// checkpoint). Also throws SettingsError for a start that does not fit the settings.
  static RenderResult render(const Scene& scene, const RenderSettings& settings,
                             const RenderControl& control, const RenderStart& from = {});

  /// Renders the work `source` hands out on settings.threads threads (0: one per hardware thread;
  /// never more than there are tiles), adding each piece's samples to `sums` (of the settings'
  /// size), and returns once next() has returned nullopt to every thread. No thread asks for
  /// work before all have started. A piece's pixels get exactly render()'s arithmetic, so
  /// sums built piece by piece, in any order and by any number of calls (in other processes
  /// too), are render()'s bit for bit as long as each pixel's samples come in index order.
  /// The result counts what this call rendered: its samples, rays, invalid samples, threads
  /// and time. Throws as render() does, and, before any work is asked for, SettingsError for
  /// sums of another size or without the splat layer the execution model needs.
  ///
  /// With a light phase (vertex merging: kExecutionHasLightPhase), a sample index's tiles need
  /// that index's light phase, which this call runs, on all its threads, before the first of
  /// them; it holds one index's light phase at a time. So a source should hand out pieces of
  /// one sample index each, and the next index's only once the last index's have finished (as
  /// render() does, and glint-render-mpi): any other order gives the same sums, with the light
  /// phase run again at each change of index, and its threads waiting for each other there.
  template <TileWorkSource Source>
  static RenderStats render_tiles(const Scene& scene, const RenderSettings& settings,
                                  PixelSums& sums, Source& source) {
    return render_tiles(scene, settings, sums, TileWorkSourceRef(source));
  }
  /// render_tiles for any source: the form a compiled renderer holds.
  static RenderStats render_tiles(const Scene& scene, const RenderSettings& settings,
                                  PixelSums& sums, TileWorkSourceRef source);

 private:
  /// The pass to begin with; throws SettingsError for a start that cannot belong to a render
  /// with these settings.
  static std::size_t check_start(const RenderStart& start, const RenderSettings& settings,
                                 std::size_t pass_count) {
    const auto fail = [](const std::string& problem) {
      throw SettingsError("glint: cannot start the render there: " + problem);
    };
    if (start.passes_done < 0 || std::size_t(start.passes_done) > pass_count)
      fail(std::to_string(start.passes_done) + " passes done, of " + std::to_string(pass_count));
    if (!start.sums) {
      if (start.passes_done != 0) fail("passes done without their sums");
    } else if (start.sums->has_splats() != kExecutionSplats<E>) {
      fail(start.sums->has_splats() ? "sums with splats for a renderer that makes none"
                                    : "sums without the splats this renderer makes");
    } else if (start.sums->width() != settings.width || start.sums->height() != settings.height) {
      fail("sums of " + std::to_string(start.sums->width()) + "x" +
           std::to_string(start.sums->height()) + " pixels for an image of " +
           std::to_string(settings.width) + "x" + std::to_string(settings.height));
    }
    return std::size_t(start.passes_done);
  }

  /// The threads a render with these settings uses for `tiles` tiles.
  static int threads_for(const RenderSettings& settings, std::size_t tiles) {
    const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    return static_cast<int>(
        std::min<std::size_t>(settings.threads > 0 ? settings.threads : hardware, tiles));
  }

  /// Each thread's scratch memory, allocated here, before any thread starts, so that a lack of
  /// memory is an exception on the caller's thread and not a failure inside a worker.
  static std::vector<typename E::ThreadState> thread_states(const E& execution, int count) {
    std::vector<typename E::ThreadState> states;
    states.reserve(std::size_t(count));
    for (int t = 0; t < count; ++t)
      states.emplace_back(execution);
    return states;
  }

  /// Starts `count` threads running body(t) for t = 0, 1, ...; throws Error, saying how many
  /// started, if one cannot be. Those already started are left to the caller's clean-up.
  template <typename Body>
  static void start_threads(std::vector<std::jthread>& threads, int count, const Body& body) {
    threads.reserve(std::size_t(count));
    for (int t = 0; t < count; ++t) {
      try {
        threads.emplace_back(body, t);
      } catch (const std::system_error& error) {
        throw Error("cannot start " + std::to_string(count) + " rendering threads (started " +
                    std::to_string(t) + "): " + error.code().message() + "; ask for fewer threads");
      }
    }
  }

  /// Holds render_tiles's threads back until all have started; closed (the threads end at
  /// once) when one could not be started.
  class StartGate {
   public:
    void open() { settle(kOpen); }
    void close() { settle(kClosed); }
    /// Whether the threads may go on.
    bool wait() {
      state_.wait(kWaiting, std::memory_order_acquire);
      return state_.load(std::memory_order_acquire) == kOpen;
    }

   private:
    static constexpr int kWaiting = 0, kOpen = 1, kClosed = 2;
    void settle(int state) {
      int waiting = kWaiting;
      if (state_.compare_exchange_strong(waiting, state, std::memory_order_acq_rel))
        state_.notify_all();
    }
    std::atomic<int> state_{kWaiting};
  };

  // Padded to a cache line so that threads never write to the same line. `samples` is written
  // by its worker alone (a plain store) and read by the progress reports.
  struct alignas(64) PaddedCounters {
    TraceCounters counters;
    std::atomic<std::uint64_t> samples{0};
  };

  /// Who renders what and when. Work items are numbered across passes (item i is tile
  /// i % tiles of pass i / tiles) and taken from one counter, so a worker never needs to know
  /// where a pass ends; it waits only when its item belongs to a pass not yet released. A pass
  /// is released when the one before has completed, because a tile's sums carry over.
  class Schedule {
   public:
    /// Passes before `first_pass` count as done: their sums are already in the film. `ends`
    /// (pass_ends) outlives the schedule.
    Schedule(std::size_t tiles, const std::vector<int>& ends, std::size_t first_pass)
        : tiles_(tiles),
          ends_(ends),
          items_(tiles * ends.size()),
          next_item_(tiles * first_pass),
          items_done_(tiles * first_pass),
          released_(static_cast<long long>(first_pass)) {}

    /// The next item for a worker, once its pass is released; nullopt when there is nothing
    /// more to do (all items taken, or the render stopped).
    std::optional<TileWork> next() {
      const std::size_t item = next_item_.fetch_add(1, std::memory_order_relaxed);
      if (item >= items_) return std::nullopt;
      const auto pass = static_cast<long long>(item / tiles_);
      // Acquire: the sums of the pass before, written by other workers, are visible.
      for (long long released = released_.load(std::memory_order_acquire); released <= pass;
           released = released_.load(std::memory_order_acquire)) {
        if (released == kStopped) return std::nullopt;
        released_.wait(released, std::memory_order_acquire);
      }
      const auto p = std::size_t(pass);
      return TileWork{item % tiles_, p == 0 ? 0 : ends_[p - 1], ends_[p], item};
    }

    /// A worker finished an item. Release: its sums are visible to whoever sees the count.
    void finished(const TileWork& work) {
      const std::size_t pass_end = (work.id / tiles_ + 1) * tiles_;
      if (items_done_.fetch_add(1, std::memory_order_acq_rel) + 1 == pass_end) {
        // The lock, once per pass, keeps the caller from missing the wake-up between its
        // check and its wait.
        const std::lock_guard<std::mutex> lock(mutex_);
        pass_complete_.notify_all();
      }
    }

    void release(std::size_t pass) {
      released_.store(static_cast<long long>(pass) + 1, std::memory_order_release);
      released_.notify_all();
    }
    void stop() {
      released_.store(kStopped, std::memory_order_release);
      released_.notify_all();
    }

    /// Whether `pass` completed within `timeout`.
    bool wait_for_pass(std::size_t pass, std::chrono::milliseconds timeout) {
      std::unique_lock<std::mutex> lock(mutex_);
      return pass_complete_.wait_for(lock, timeout, [&] {
        return items_done_.load(std::memory_order_acquire) >= (pass + 1) * tiles_;
      });
    }

   private:
    static constexpr long long kStopped = LLONG_MIN;
    const std::size_t tiles_;
    const std::vector<int>& ends_;
    const std::size_t items_;
    std::atomic<std::size_t> next_item_;
    std::atomic<std::size_t> items_done_;
    std::atomic<long long> released_;  ///< passes released, or kStopped
    std::mutex mutex_;
    std::condition_variable pass_complete_;
  };

  struct StopWorkersOnExit {
    Schedule& schedule;
    ~StopWorkersOnExit() { schedule.stop(); }
  };

  /// render_tiles's light phases (where E has them): the sample index whose light phase the
  /// execution holds, and the threads rendering tiles with it. A thread that needs another
  /// index waits until none renders, runs that index's light phase (on every thread: the
  /// others wait) and renders its tile; a thread that needs the index held renders at once.
  /// Each light phase is followed by at least one tile of its index, so the threads always
  /// move on, whatever order the pieces come in.
  class LightPhases {
   public:
    LightPhases(E& execution, int threads) : execution_(execution), threads_(threads) {}

    /// Renders sample `sample` of a tile by `render`, after its index's light phase.
    template <typename Render>
    void with_light_phase(int sample, const Render& render) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return !preparing_ && (held_ == sample || rendering_ == 0); });
        if (held_ != sample) {
          // No thread renders, and none can begin: the light phase has the execution to itself.
          preparing_ = true;
          lock.unlock();
          if constexpr (kExecutionHasLightPhase<E>)
            execution_.prepare_sample(sample, threads_, counters_);
          lock.lock();
          held_ = sample;
          preparing_ = false;
          changed_.notify_all();
        }
        ++rendering_;
      }
      render();
      const std::lock_guard<std::mutex> lock(mutex_);
      if (--rendering_ == 0) changed_.notify_all();
    }
    const E& execution() const { return execution_; }
    /// The light phases' rays; read once the threads have ended.
    const TraceCounters& counters() const { return counters_; }

   private:
    E& execution_;
    const int threads_;
    std::mutex mutex_;
    std::condition_variable changed_;
    int held_ = -1;  ///< the sample index of the light phase held, or -1
    int rendering_ = 0;
    bool preparing_ = false;
    TraceCounters counters_;
  };

  /// A rendering thread of render_tiles with light phases: the work of `source` until it has
  /// none left, each sample index of a piece after its light phase.
  template <typename Source>
  static void work_after_light_phases(Source& source, const TileGrid& grid, LightPhases& phases,
                                      typename E::ThreadState& state, PixelSums& sums,
                                      PaddedCounters& mine) {
    std::uint64_t samples = 0;
    for (std::optional<TileWork> piece = source.next(); piece; piece = source.next()) {
      for (int s = piece->first_sample; s < piece->last_sample; ++s)
        phases.with_light_phase(s, [&] {
          phases.execution().render_tile(state, grid.tile(piece->tile), s, s + 1, sums,
                                         mine.counters, mine.samples, samples);
        });
      source.finished(*piece);
    }
  }

  /// A rendering thread: the work of `source` until it has none left.
  template <typename Source>
  static void work(Source& source, const TileGrid& grid, const E& execution,
                   typename E::ThreadState& state, PixelSums& sums, PaddedCounters& mine) {
    std::uint64_t samples = 0;
    for (std::optional<TileWork> piece = source.next(); piece; piece = source.next()) {
      execution.render_tile(state, grid.tile(piece->tile), piece->first_sample, piece->last_sample,
                            sums, mine.counters, mine.samples, samples);
      source.finished(*piece);
    }
  }
};

// The renderer's work is defined outside the class: an explicit instantiation declaration
// (`extern template class Renderer<...>;`) then keeps a translation unit from compiling it, so
// that a program can compile each of its renderers once, in a file of its own (glint's own
// programs do: cmake/GlintRenderers.cmake).

template <RenderConfig C, Execution E>
RenderResult Renderer<C, E>::render(const Scene& scene, const RenderSettings& settings,
                                    const RenderControl& control, const RenderStart& from) {
  validate(settings);
  check_supported<C>(scene);
  check_work<C>(scene, settings.max_depth);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  const std::vector<int> ends = pass_ends(settings.samples_per_pixel, settings.max_pass_samples);
  const std::size_t first_pass = check_start(from, settings, ends.size());

  PixelSums sums =
      from.sums ? *from.sums : PixelSums(settings.width, settings.height, kExecutionSplats<E>);
  RenderResult result{
      {}, {}, first_pass ? ends[first_pass - 1] : 0, int(first_pass), int(ends.size()), {}};
  E execution(scene, settings);

  const TileGrid grid(settings);
  const int thread_count = threads_for(settings, grid.count);
  const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);

  // The steps the workers are released for: the passes, or with a light phase each sample index.
  std::vector<int> steps = ends;
  if constexpr (kExecutionHasLightPhase<E>) {
    steps.resize(std::size_t(settings.samples_per_pixel));
    for (std::size_t i = 0; i < steps.size(); ++i)
      steps[i] = int(i) + 1;
  }
  std::size_t step =
      kExecutionHasLightPhase<E> ? std::size_t(result.samples_per_pixel) : first_pass;
  Schedule schedule(grid.count, steps, step);
  TraceCounters light_phase_counters;
  std::vector<PaddedCounters> counters(static_cast<std::size_t>(thread_count));
  std::vector<typename E::ThreadState> states = thread_states(execution, thread_count);
  {
    std::vector<std::jthread> workers;
    // Declared after the workers so that it runs before they are joined: on any way out
    // (a callback that throws included) no worker is left waiting for a pass.
    const StopWorkersOnExit stop_workers{schedule};
    start_threads(workers, thread_count, [&](int t) {
      work(schedule, grid, execution, states[std::size_t(t)], sums, counters[std::size_t(t)]);
    });

    const std::uint64_t samples_at_start = pixels * std::uint64_t(result.samples_per_pixel);
    const auto report = [&](bool last) {
      if (!control.progress) return;
      std::uint64_t done = samples_at_start;
      for (const PaddedCounters& c : counters)
        done += c.samples.load(std::memory_order_relaxed);
      const int spp_done = result.passes_done ? ends[std::size_t(result.passes_done) - 1] : 0;
      control.progress(RenderProgress{done, pixels * std::uint64_t(settings.samples_per_pixel),
                                      elapsed(), result.passes_done, result.pass_count, spp_done,
                                      last, samples_at_start});
    };
    for (std::size_t pass = first_pass; pass < ends.size(); ++pass) {
      if (control.stop && control.stop->load(std::memory_order_relaxed)) break;
      for (; step < steps.size() && steps[step] <= ends[pass]; ++step) {
        // The workers wait for the step's release: the light phase has the machine to itself.
        if constexpr (kExecutionHasLightPhase<E>)
          execution.prepare_sample(steps[step] - 1, thread_count, light_phase_counters);
        schedule.release(step);
        while (!schedule.wait_for_pass(step, progress_interval))
          report(false);
      }
      result.passes_done = int(pass) + 1;
      result.samples_per_pixel = ends[pass];
      if (pass + 1 < ends.size()) report(false);
      if (control.pass_done &&
          !control.pass_done(PassReport{result.passes_done, result.pass_count,
                                        result.samples_per_pixel, elapsed(), sums}))
        break;
    }
    report(true);
  }  // the workers are told to stop, and join here

  if (result.samples_per_pixel > 0) {
    MeanImage image = mean_image(sums, result.samples_per_pixel);
    result.film = std::move(image.film);
    result.stats.clamped_pixels = image.clamped_pixels;
  } else {
    result.film = Film(settings.width, settings.height);
  }
  if (control.keep_sums) result.sums = std::move(sums);
  for (const PaddedCounters& c : counters) {
    result.stats.rays += c.counters.rays;
    result.stats.invalid_samples += c.counters.invalid_samples;
  }
  result.stats.rays += light_phase_counters.rays;
  result.stats.invalid_samples += light_phase_counters.invalid_samples;
  result.stats.samples = pixels * std::uint64_t(result.samples_per_pixel);
  result.stats.threads = thread_count;
  result.stats.seconds = elapsed();
  return result;
}

template <RenderConfig C, Execution E>
RenderStats Renderer<C, E>::render_tiles(const Scene& scene, const RenderSettings& settings,
                                         PixelSums& sums, TileWorkSourceRef source) {
  validate(settings);
  check_supported<C>(scene);
  check_work<C>(scene, settings.max_depth);
  if (sums.width() != settings.width || sums.height() != settings.height)
    throw SettingsError("glint: sums of " + std::to_string(sums.width()) + "x" +
                        std::to_string(sums.height()) + " pixels for an image of " +
                        std::to_string(settings.width) + "x" + std::to_string(settings.height));
  if (sums.has_splats() != kExecutionSplats<E>)
    throw SettingsError(sums.has_splats() ? "glint: sums with splats for a renderer that makes none"
                                          : "glint: sums without the splats this renderer makes");
  const auto start = std::chrono::steady_clock::now();
  E execution(scene, settings);
  const TileGrid grid(settings);
  const int thread_count = threads_for(settings, grid.count);
  std::vector<PaddedCounters> counters(static_cast<std::size_t>(thread_count));
  std::vector<typename E::ThreadState> states = thread_states(execution, thread_count);
  LightPhases light_phases(execution, thread_count);
  {
    // Declared before the threads, so that it outlives them: each reads it until it ends.
    StartGate gate;
    std::vector<std::jthread> threads;
    try {
      start_threads(threads, thread_count, [&](int t) {
        if (!gate.wait()) return;
        if constexpr (kExecutionHasLightPhase<E>)
          work_after_light_phases(source, grid, light_phases, states[std::size_t(t)], sums,
                                  counters[std::size_t(t)]);
        else
          work(source, grid, execution, states[std::size_t(t)], sums, counters[std::size_t(t)]);
      });
    } catch (...) {
      gate.close();  // the threads already started end, without asking for work, and join
      throw;
    }
    gate.open();
  }
  RenderStats stats;
  for (const PaddedCounters& c : counters) {
    stats.rays += c.counters.rays;
    stats.invalid_samples += c.counters.invalid_samples;
    stats.samples += c.samples.load(std::memory_order_relaxed);
  }
  stats.rays += light_phases.counters().rays;
  stats.invalid_samples += light_phases.counters().invalid_samples;
  stats.threads = thread_count;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
