// mpi_coordinator.hpp's definitions.

#include "mpi_coordinator.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "glint/image/film.hpp"
#include "mpi_measures.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

glint::RenderResult Coordinator::render(const glint::RenderControl& control, int first_pass) {
  const auto start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const std::uint64_t pixels = std::uint64_t(settings_.width) * std::uint64_t(settings_.height);
  glint::RenderResult result{
      {}, {}, first_pass ? ends_[std::size_t(first_pass) - 1] : 0, first_pass, int(ends_.size()),
      {}};
  const std::uint64_t samples_at_start = pixels * std::uint64_t(result.samples_per_pixel);
  samples_done_ = samples_at_start;
  double last_report = -1.0;
  const auto report = [&](bool last) {
    if (!control.progress) return;
    last_report = elapsed();
    control.progress(glint::RenderProgress{
        samples_done_, pixels * std::uint64_t(settings_.samples_per_pixel), last_report,
        result.passes_done, result.pass_count, result.samples_per_pixel, last, samples_at_start});
  };
  first_pass_ = std::size_t(first_pass);
  step_ = std::size_t(std::upper_bound(steps_.begin(), steps_.end(), result.samples_per_pixel) -
                      steps_.begin());
  const std::function<void()> report_now = [&] {
    if (elapsed() - last_report >= 0.1) report(false);
  };
  for (pass_ = first_pass_; pass_ < ends_.size(); ++pass_) {
    if (control.stop && control.stop->load(std::memory_order_relaxed)) break;
    const double pass_start = elapsed();
    traffic_.emplace_back();
    counting_ = &traffic_.back();
    for (; step_ < steps_.size() && steps_[step_] <= ends_[pass_]; ++step_)
      render_step(report_now);
    if (sums_.has_splats()) gather_splats();
    traffic_.back().seconds = elapsed() - pass_start;
    counting_ = &between_passes_;
    result.passes_done = int(pass_) + 1;
    result.samples_per_pixel = ends_[pass_];
    if (pass_ + 1 < ends_.size()) report(false);
    if (control.pass_done &&
        !control.pass_done(glint::PassReport{result.passes_done, result.pass_count,
                                             result.samples_per_pixel, elapsed(), sums_}))
      break;
  }
  report(true);
  stop_workers();
  renderer_.finish();
  if (const std::optional<Failure> failure = renderer_.failed()) abort_run(failure->message);
  reports_ = gather_reports(world_, renderer_, local_tiles_);

  if (result.samples_per_pixel > 0) {
    glint::MeanImage image = glint::mean_image(sums_, result.samples_per_pixel);
    result.film = std::move(image.film);
    result.stats.clamped_pixels = image.clamped_pixels;
  } else {
    result.film = glint::Film(settings_.width, settings_.height);
  }
  for (const RankReport& rank : reports_) {
    result.stats.rays += rank.rays;
    result.stats.invalid_samples += rank.invalid_samples;
    result.stats.threads += rank.threads;
  }
  result.stats.samples = pixels * std::uint64_t(result.samples_per_pixel);
  result.stats.seconds = elapsed();
  return result;
}

std::string Coordinator::workers() const {
  std::string text = std::to_string(world_.size) + (world_.size == 1 ? " rank" : " ranks");
  const bool same = std::all_of(reports_.begin(), reports_.end(), [&](const RankReport& r) {
    return r.threads == reports_.front().threads;
  });
  if (same) return text + " x " + std::to_string(reports_.front().threads) + " threads";
  int total = 0;
  std::string each;
  for (const RankReport& r : reports_) {
    total += r.threads;
    if (!each.empty()) each += '+';
    each += std::to_string(r.threads);
  }
  return text + ", " + std::to_string(total) + " threads (" + each + ")";
}

std::string Coordinator::report_lines(bool verbose) const {
  PassTraffic total = between_passes_;
  for (const PassTraffic& t : traffic_) {
    total.bytes_in += t.bytes_in;
    total.messages_in += t.messages_in;
    total.bytes_out += t.bytes_out;
    total.messages_out += t.messages_out;
    total.sums_back += t.sums_back;
    total.sums_moved += t.sums_moved;
    total.splats_in += t.splats_in;
    total.tiles_moved += t.tiles_moved;
  }
  const std::string& name = world_.program;
  std::string text = name + ": idle:";
  char line[256];
  for (std::size_t r = 0; r < reports_.size(); ++r) {
    const RankReport& rank = reports_[r];
    std::snprintf(line, sizeof line, "%s rank %zu %.2f s (%.0f%%)", r ? "," : "", r,
                  rank.idle_seconds,
                  100.0 * rank.idle_seconds / std::max(rank.window_seconds, 1e-9));
    text += line;
  }
  text += "; sent " + megabytes(total.bytes_in + total.bytes_out) + " in " +
          std::to_string(total.messages_in + total.messages_out) + " messages (sums back " +
          megabytes(total.sums_back) + ", moved " + megabytes(total.sums_moved) + ", " +
          std::to_string(total.tiles_moved) + " tiles)";
  if (sums_.has_splats()) text += ", splats " + megabytes(total.splats_in) + " summed";
  text += "\n";
  if (!verbose) return text;
  for (std::size_t p = 0; p < traffic_.size(); ++p) {
    const PassTraffic& t = traffic_[p];
    std::snprintf(line, sizeof line,
                  "%s: pass %zu (%d spp): %.3f s; to rank 0 %s in %llu messages, from rank 0 %s "
                  "in %llu messages; %llu tiles moved (%s of sums)\n",
                  name.c_str(), first_pass_ + p + 1, ends_[first_pass_ + p], t.seconds,
                  megabytes(t.bytes_in).c_str(), static_cast<unsigned long long>(t.messages_in),
                  megabytes(t.bytes_out).c_str(), static_cast<unsigned long long>(t.messages_out),
                  static_cast<unsigned long long>(t.tiles_moved), megabytes(t.sums_moved).c_str());
    text += line;
  }
  for (std::size_t r = 0; r < reports_.size(); ++r) {
    const RankReport& rank = reports_[r];
    std::snprintf(line, sizeof line,
                  "%s: rank %zu: %d threads, %llu tiles, %.2f Mrays, idle %.3f s of %.3f s per "
                  "thread; main thread %.3f s of CPU\n",
                  name.c_str(), r, rank.threads, static_cast<unsigned long long>(rank.tiles),
                  double(rank.rays) * 1e-6, rank.idle_seconds, rank.window_seconds,
                  rank.main_cpu_seconds);
    text += line;
  }
  return text;
}

void Coordinator::render_step(const std::function<void()>& report) {
  scheduler_.begin_pass();
  for (int r = 1; r < world_.size; ++r)
    if (asked_[std::size_t(r)] > 0) hand_out(r, std::exchange(asked_[std::size_t(r)], 0));
  while (!scheduler_.pass_complete()) {
    poll_round();
    report();
    if (!scheduler_.pass_complete()) renderer_.queue().wait(kPollInterval);
  }
  counting_->tiles_moved += scheduler_.moved();
}

void Coordinator::gather_splats() {
  // Every tile of the pass has finished, and no rank has another: no thread splats anywhere.
  for (int r = 1; r < world_.size; ++r)
    outbox_.send(r, kTagSplats, {});
  outbox_.flush();
  sum_splats(0, sums_.splats());
  counting_->splats_in +=
      std::uint64_t(world_.size - 1) * sums_.splats().words().size() * sizeof(std::int64_t);
}

void Coordinator::poll_round() {
  outbox_.progress();
  while (std::optional<Message> message = poll())
    receive(*message);
  if (const std::optional<Failure> failure = renderer_.failed()) abort_run(failure->message);
  TileQueue& queue = renderer_.queue();
  for (const glint::TileWork& work : queue.take_finished()) {
    scheduler_.finished();
    samples_done_ +=
        grid_.tile(work.tile).pixel_count() * std::uint64_t(work.last_sample - work.first_sample);
    ++local_tiles_;
  }
  if (const std::size_t want = tiles_wanted(queue.queued(), threads_); want > 0)
    for (const TileScheduler::Assignment& a : scheduler_.assign(0, want))
      queue.add({a.tile, samples().first, samples().last, 0});
}

void Coordinator::receive(const Message& message) {
  if (message.tag == kTagFailed)
    abort_run(describe_failure(world_, message.source,
                               std::string(message.bytes.begin(), message.bytes.end())));
  const auto protocol_error = [&](const char* what) {
    abort_run(world_.program + ": error: rank " + std::to_string(message.source) + " sent " + what +
              "\n");
  };
  if (message.tag != kTagWork) protocol_error("an unexpected message");
  try {
    PassTraffic& traffic = *counting_;
    traffic.bytes_in += message.bytes.size();
    ++traffic.messages_in;
    Unpacker in(message.bytes);
    const auto want = in.get<std::uint32_t>();
    const auto count = in.get<std::uint32_t>();
    for (std::uint32_t i = 0; i < count; ++i) {
      const auto tile = in.get<std::uint32_t>();
      const auto done = in.get<PassSamples>();
      if (tile >= grid_.count || scheduler_.holder(tile) != message.source ||
          done.first != samples().first || done.last != samples().last)
        protocol_error("a tile it was not given");
      in.get_sums(grid_.tile(tile), sums_);
      traffic.sums_back += grid_.tile(tile).pixel_count() * sizeof(glint::ColorSum);
      scheduler_.finished();
      samples_done_ += grid_.tile(tile).pixel_count() * std::uint64_t(done.last - done.first);
    }
    if (!in.done()) protocol_error("a message longer than its fields");
    if (want > 0) hand_out(message.source, want);
  } catch (const std::runtime_error& error) {
    protocol_error(error.what());
  }
}

void Coordinator::hand_out(int rank, std::uint32_t want) {
  // Between passes every queue is empty: the request waits for the next pass.
  const std::vector<TileScheduler::Assignment> given = scheduler_.assign(rank, want);
  if (given.empty()) {
    asked_[std::size_t(rank)] = want;
    return;
  }
  Packer out;
  out.put(samples());
  out.put(std::uint32_t(given.size()));
  PassTraffic& traffic = *counting_;
  for (const TileScheduler::Assignment& a : given) {
    out.put(std::uint32_t(a.tile));
    out.put(std::uint8_t(a.send_sums));
    if (!a.send_sums) continue;
    out.put_sums(grid_.tile(a.tile), sums_);
    traffic.sums_moved += grid_.tile(a.tile).pixel_count() * sizeof(glint::ColorSum);
  }
  std::vector<char> bytes = out.take();
  traffic.bytes_out += bytes.size();
  ++traffic.messages_out;
  outbox_.send(rank, kTagAssign, std::move(bytes));
}

void Coordinator::stop_workers() {
  const auto all_asked = [&] {
    for (int r = 1; r < world_.size; ++r)
      if (asked_[std::size_t(r)] == 0) return false;
    return true;
  };
  while (!all_asked()) {
    outbox_.progress();
    while (std::optional<Message> message = poll())
      receive(*message);
    std::this_thread::sleep_for(kPollInterval);
  }
  for (int r = 1; r < world_.size; ++r)
    outbox_.send(r, kTagStop, {});
  outbox_.flush();
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
