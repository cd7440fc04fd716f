#pragma once
// glint-render-mpi's scheduling, apart from MPI so that it can be tested alone.
//
// TileScheduler is rank 0's hand-out of a render's tiles, pass by pass. A tile's sums carry
// over from pass to pass, so whoever renders a tile must start from the sums its last pass
// left: the rank that rendered it last (its holder) has them, and rank 0, to which every
// finished tile's sums come back, has them too. Each pass, a rank first gets the tiles it
// holds (nothing to send), in order, a batch at a time; a rank with none left takes, from the
// back, some of the rank with the most left, and then rank 0 sends their sums with them. So
// each rank keeps the share its speed earned in the pass before, and the end of a pass is
// evened out by stealing.
//
// TileQueue is how one rank's rendering threads (Renderer::render_tiles) get the tiles its
// main thread receives, and give back the finished ones; it measures how long they wait.

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/render/renderer.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

class TileScheduler {
 public:
  /// A tile given to a rank; `send_sums`: the rank lacks the tile's sums, which go with it.
  struct Assignment {
    std::size_t tile;
    bool send_sums;
  };

  /// `tiles` tiles over `ranks` ranks. `sums_everywhere`: the render starts from zero sums,
  /// which every rank has (a new render); otherwise rank 0 alone holds them (a resumed one).
  TileScheduler(std::size_t tiles, int ranks, bool sums_everywhere)
      : holder_(tiles, sums_everywhere ? kEveryone : 0), queues_(std::size_t(ranks)) {}

  /// Every tile becomes pending: in its holder's queue, or in the common one.
  void begin_pass() {
    for (std::deque<std::size_t>& queue : queues_)
      queue.clear();
    common_.clear();
    for (std::size_t tile = 0; tile < holder_.size(); ++tile)
      (holder_[tile] == kEveryone ? common_ : queues_[std::size_t(holder_[tile])]).push_back(tile);
    finished_ = 0;
    moved_ = 0;
  }

  /// Up to `count` pending tiles for `rank`, who holds them from now on: its own first, then
  /// tiles anyone can start (zero sums), then tiles stolen from the back of the longest queue.
  /// Empty when no tile of the pass is pending.
  std::vector<Assignment> assign(int rank, std::size_t count) {
    std::vector<Assignment> out;
    std::deque<std::size_t>& own = queues_[std::size_t(rank)];
    while (out.size() < count) {
      std::size_t tile;
      bool send = false;
      if (!own.empty()) {
        tile = own.front();
        own.pop_front();
      } else if (!common_.empty()) {
        tile = common_.front();
        common_.pop_front();
      } else {
        const auto longest =
            std::max_element(queues_.begin(), queues_.end(),
                             [](const auto& a, const auto& b) { return a.size() < b.size(); });
        if (longest->empty()) break;
        tile = longest->back();
        longest->pop_back();
        // Rank 0 renders into the sums every finished tile comes back to.
        send = rank != 0;
        ++moved_;
      }
      holder_[tile] = rank;
      out.push_back({tile, send});
    }
    return out;
  }

  void finished() { ++finished_; }
  bool pass_complete() const { return finished_ == holder_.size(); }
  std::size_t tiles() const { return holder_.size(); }
  /// Tiles that changed ranks in this pass so far.
  std::size_t moved() const { return moved_; }
  /// The rank that rendered the tile last, or -1 for none yet.
  int holder(std::size_t tile) const { return holder_[tile]; }

 private:
  static constexpr int kEveryone = -1;
  std::vector<int> holder_;
  std::vector<std::deque<std::size_t>> queues_;
  std::deque<std::size_t> common_;
  std::size_t finished_ = 0;
  std::size_t moved_ = 0;
};

/// A TileWorkSource between a rank's main thread, which adds tiles and collects finished ones,
/// and its rendering threads. Locked once per tile, never per sample.
class TileQueue {
 public:
  using Clock = std::chrono::steady_clock;

  // For Renderer::render_tiles, on the rendering threads.
  std::optional<TileWork> next() {
    std::unique_lock<std::mutex> lock(mutex_);
    asked_ = true;
    const Clock::time_point start = Clock::now();
    work_ready_.wait(lock, [&] { return !queue_.empty() || closed_; });
    waited_ += Clock::now() - start;
    if (queue_.empty()) return std::nullopt;
    const TileWork work = queue_.front();
    queue_.pop_front();
    return work;
  }
  void finished(const TileWork& work) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      finished_.push_back(work);
    }
    event_.notify_one();
  }

  // On the main thread.
  void add(const TileWork& work) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(work);
    }
    work_ready_.notify_one();
  }
  /// The tiles finished since the last call.
  std::vector<TileWork> take_finished() {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::vector<TileWork> done(finished_.begin(), finished_.end());
    finished_.clear();
    return done;
  }
  /// Tiles added and not yet taken by a thread.
  std::size_t queued() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return queue_.size();
  }
  /// After it, next() returns nullopt once the queue is empty.
  void close() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    work_ready_.notify_all();
    event_.notify_all();
  }
  /// Waits up to `timeout` for a finished tile, a stop of the rendering (notify()) or nothing.
  void wait(std::chrono::microseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    event_.wait_for(lock, timeout, [&] { return !finished_.empty() || notified_; });
    notified_ = false;
  }
  /// Wakes wait(): the rendering has ended (or failed).
  void notify() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      notified_ = true;
    }
    event_.notify_all();
  }
  /// Whether a thread has asked for work: render_tiles lets none ask before all have started.
  bool threads_started() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return asked_;
  }
  /// The time the rendering threads spent waiting for work, added over the threads.
  double waited_seconds() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::chrono::duration<double>(waited_).count();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable event_;
  std::deque<TileWork> queue_;
  std::deque<TileWork> finished_;
  Clock::duration waited_{};
  bool closed_ = false;
  bool notified_ = false;
  bool asked_ = false;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
