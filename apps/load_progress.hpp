#pragma once
// glint-render's report while a scene loads. A scene that loads within a second prints
// nothing; a slower one (millions of spheres) shows its stage (reading, parsing, building)
// and how far it has got: one line redrawn in place on a terminal, a line per stage and per
// tenth of a stage otherwise, then a line with the spheres and the time taken. The reader
// only stores its position (SceneReadCallback); a thread of this class prints, so the report
// keeps moving during a stage that reports nothing (building the scene).

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>

#include "glint/instruction_set.hpp"
#include "glint/io/scene_reader.hpp"
#include "progress_printer.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

enum class LoadStage { reading, parsing, building };

/// "reading 45%", "parsing", "building the scene of 1000000 spheres" (what `count` means
/// depends on the stage: a percentage while reading or parsing, spheres while building; -1:
/// unknown).
inline std::string describe_load_stage(LoadStage stage, long long count) {
  switch (stage) {
    case LoadStage::reading:
    case LoadStage::parsing: {
      std::string text = stage == LoadStage::reading ? "reading" : "parsing";
      return count < 0 ? text : text + " " + std::to_string(count) + "%";
    }
    case LoadStage::building:
      return "building the scene of " + std::to_string(count) + " spheres";
  }
  return "";
}

class LoadProgress {
 public:
  /// Prints to `out` once loading has taken `delay`, on one redrawn line if `terminal`.
  LoadProgress(bool enabled, std::string scene, std::FILE* out = stderr,
               std::chrono::milliseconds delay = std::chrono::seconds(1),
               bool terminal = isatty(2) != 0)
      : scene_(std::move(scene)), out_(out), delay_(delay), terminal_(terminal) {
    if (enabled) printer_ = std::jthread([this](std::stop_token stop) { run(stop); });
  }
  /// Without finished() (a scene error on its way out), ends a redrawn line before the error.
  ~LoadProgress() {
    stop();
    if (printed_ && terminal_ && !finished_) std::fputc('\n', out_);
  }
  LoadProgress(const LoadProgress&) = delete;
  LoadProgress& operator=(const LoadProgress&) = delete;

  /// For read_scene_file.
  SceneReadCallback reader_callback() {
    return [this](const SceneReadProgress& p) {
      const long long percent = p.total ? static_cast<long long>(p.done * 100 / p.total) : -1;
      set(p.stage == SceneReadProgress::Stage::reading ? LoadStage::reading : LoadStage::parsing,
          percent);
    };
  }
  void building(std::size_t spheres) { set(LoadStage::building, static_cast<long long>(spheres)); }

  /// Loading is over: ends the report with the time taken, if anything was printed.
  void finished(std::size_t spheres) {
    stop();
    finished_ = true;
    if (!printed_) return;
    std::fprintf(out_, "%sloaded %s: %zu spheres in %s%s\n", terminal_ ? "\r" : "", scene_.c_str(),
                 spheres, format_seconds(elapsed()).c_str(),
                 terminal_ ? "                    " : "");
    std::fflush(out_);
  }

 private:
  void set(LoadStage stage, long long count) {
    count_.store(count, std::memory_order_relaxed);
    stage_.store(int(stage), std::memory_order_relaxed);
  }

  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  void stop() {
    if (!printer_.joinable()) return;
    printer_.request_stop();
    printer_.join();
  }

  void run(std::stop_token stop) {
    std::mutex mutex;
    std::condition_variable_any wake;
    std::unique_lock<std::mutex> lock(mutex);
    std::string last;
    while (true) {
      // Returns early, and only, when a stop is requested.
      wake.wait_for(lock, stop, std::chrono::milliseconds(100), [] { return false; });
      if (stop.stop_requested()) return;
      if (elapsed() < std::chrono::duration<double>(delay_).count()) continue;
      const auto stage = LoadStage(stage_.load(std::memory_order_relaxed));
      long long count = count_.load(std::memory_order_relaxed);
      // A log gets a line per stage and per tenth; a terminal the percentage as it moves.
      if (!terminal_ && stage != LoadStage::building && count >= 0) count -= count % 10;
      const std::string what = describe_load_stage(stage, count);
      if (!terminal_ && what == last) continue;
      last = what;
      std::fprintf(out_, "%sloading %s: %s (%s)%s", terminal_ ? "\r" : "", scene_.c_str(),
                   what.c_str(), format_seconds(elapsed()).c_str(), terminal_ ? "   " : "\n");
      std::fflush(out_);
      printed_ = true;
    }
  }

  const std::string scene_;
  std::FILE* const out_;
  const std::chrono::milliseconds delay_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::atomic<int> stage_{int(LoadStage::reading)};
  std::atomic<long long> count_{-1};
  bool printed_ = false;  // written by the printer thread, read after it has joined
  bool finished_ = false;
  std::jthread printer_;  // last: it starts once everything it reads is made
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
