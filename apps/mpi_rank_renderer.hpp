#pragma once
// One rank's rendering threads in glint-render-mpi, fed tiles by the rank's main thread, and what
// each rank reports at the end.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#include "failure.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "mpi_measures.hpp"
#include "mpi_world.hpp"
#include "program.hpp"
#include "tile_scheduler.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// How many tiles a rank with `threads` rendering threads and `queued` tiles not yet started asks
/// for: it keeps up to two per thread, and asks once one per thread or fewer are left, so that
/// every thread has a tile to go on with while the answer comes.
inline std::size_t tiles_wanted(std::size_t queued, int threads) {
  const auto per_thread = std::size_t(threads);
  return queued <= per_thread ? 2 * per_thread - queued : 0;
}

/// The render of the tiles a TileQueue hands out, until it is closed: the execution model's
/// render_tiles, given by the program, which alone knows the variant.
using RenderTiles = std::function<glint::RenderStats(TileQueue& queue)>;

/// One rank's rendering threads, running `render_tiles` on a thread of their own, fed by a
/// TileQueue.
class RankRenderer {
 public:
  RankRenderer(const Program& program, RenderTiles render_tiles)
      : start_(Clock::now()),
        main_cpu_start_(thread_cpu_seconds()),
        thread_([this, &program, render_tiles = std::move(render_tiles)] {
          try {
            stats_ = render_tiles(queue_);
          } catch (...) {
            failure_ = current_failure(program);
          }
          ended_.store(true);
          queue_.notify();
        }) {}
  ~RankRenderer() {
    queue_.close();
    if (thread_.joinable()) thread_.join();
  }
  RankRenderer(const RankRenderer&) = delete;
  RankRenderer& operator=(const RankRenderer&) = delete;

  /// Waits until the threads have started (and asked for work), or failed to.
  std::optional<Failure> started() {
    while (!queue_.threads_started() && !ended_.load())
      queue_.wait(std::chrono::milliseconds(1));
    return failed();
  }
  /// What went wrong, once the rendering has ended by an error.
  std::optional<Failure> failed() const { return ended_.load() ? failure_ : std::nullopt; }
  /// Ends the rendering once the queue is empty, and waits for it.
  void finish() {
    queue_.close();
    thread_.join();
    window_ = std::chrono::duration<double>(Clock::now() - start_).count();
  }
  TileQueue& queue() { return queue_; }
  const glint::RenderStats& stats() const { return stats_; }
  /// Since the threads started, until finish().
  double window_seconds() const { return window_; }
  /// The CPU time of the calling (main) thread since the threads started.
  double main_cpu_seconds() const { return thread_cpu_seconds() - main_cpu_start_; }

 private:
  TileQueue queue_;
  glint::RenderStats stats_;
  std::optional<Failure> failure_;
  std::atomic<bool> ended_{false};
  Clock::time_point start_;
  double main_cpu_start_;
  double window_ = 0.0;
  std::thread thread_;  // last: it starts once everything it uses is made
};

/// What each rank tells rank 0 at the end.
struct RankReport {
  double idle_seconds = 0.0;    ///< its threads' waiting for work, per thread
  double window_seconds = 0.0;  ///< from its threads' start to the end
  std::uint64_t rays = 0;
  std::uint64_t invalid_samples = 0;
  std::uint64_t tiles = 0;        ///< tiles rendered, over all passes
  double main_cpu_seconds = 0.0;  ///< its main thread's: messages, scheduling, waiting
  std::int32_t threads = 0;
};

/// Every rank's report, in rank order, on rank 0 (the other ranks get none of use): called by every
/// rank once its renderer has finished, with the tiles it rendered.
std::vector<RankReport> gather_reports(const World& world, RankRenderer& renderer,
                                       std::uint64_t tiles);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
