// glint-render-mpi: glint-render on several processes, with MPI (`mpirun -n N glint-render-mpi
// SCENE [options]`), writing the image glint-render writes with the same options, bit for bit.
// Built for the default variant only (GLINT_VARIANT, as glint-render), with its wavefront
// renderer by default and its scalar one with --scalar (render_variant.hpp's with_renderer),
// and like glint-render once per instruction set where GLINT_RENDER_SIMD_SETS says so: main
// (x86-64) initialises MPI, reads the options and runs the chosen set's entry,
// glint_render_mpi_<set>, which reads them again and renders.
//
// Every rank renders with all its threads (render_tiles); rank 0 also schedules,
// gathers and writes. The render is glint-render's passes. A pixel's sum must grow sample by
// sample in index order across passes, so whoever renders a tile in a pass starts from the sums
// that tile had after the pass before. Rank 0 hands out tiles (tile_scheduler.hpp): each rank
// asks for a batch when its threads have one tile each or fewer left in hand, and gets back
// first the tiles it rendered in the pass before, whose sums it holds, so that nothing but the
// tile numbers is sent; once none is left, it takes tiles from the rank with the most left,
// and rank 0 sends their sums with them. Each finished tile's sums go back to rank 0 with the
// next request, so that after every pass rank 0 has the whole image: for the progress, a stop
// after any pass, checkpoints (the same file as glint-render's) and the outputs. The ranks meet
// only at the end of each pass, when rank 0 holds back their requests until the next one.
//
// MPI is called from each rank's main thread only (MPI_THREAD_FUNNELED), which polls it and
// sleeps on the rendering threads' queue in between: a blocking MPI call would spin a core
// that the rendering threads need.

#include <mpi.h>
#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "glint/glint.hpp"
#include "load_progress.hpp"
#include "progress_printer.hpp"
#include "render_command.hpp"
#include "render_variant.hpp"
#include "tile_scheduler.hpp"

namespace {

using glint::cli::Variant;
namespace cli = glint::cli;
using Clock = std::chrono::steady_clock;

constexpr cli::Program kProgram{
    "glint-render-mpi",
    "usage: mpirun -n N glint-render-mpi SCENE [options]",
    R"(Renders SCENE (a glint scene file) with the path tracer on N processes (MPI ranks, on one
machine or several) and writes the image glint-render writes with the same options, bit for
bit, whatever the number of ranks and threads. Rank 0 reads SCENE and sends it to the others,
hands out the tiles, prints the progress and writes the outputs (paths are rank 0's).)",
    R"(  --threads N         rendering threads per rank (default: the CPUs the rank may run on;
                      mpirun binds each rank to one core unless given --bind-to none)
)",
    R"(  --scene-everywhere  every rank reads SCENE itself, at the same path (a shared file
                      system), instead of receiving rank 0's copy
  --verbose           after the summary, a line per pass (time, bytes sent) and per rank
                      (threads, tiles, idle time)
)",
    R"(Progress with an estimated time left goes to stderr while rendering, then one summary line
naming the ranks and threads, and a line with each rank's idle time and the bytes sent.
The image is rendered in passes (1 sample per pixel, 2, 4, ... then 32 more at a time): the
first SIGINT, SIGTERM, SIGHUP or SIGUSR1 stops after the current pass and writes the image of
the passes done, saying how many samples per pixel it holds; a second one exits at once (the
same signal again within a second is the same stop: timeout and other supervisors signal
the process and then its process group).
Open MPI's mpirun passes SIGUSR1 on to every rank as it is, but answers SIGINT and SIGTERM by
sending SIGTERM to every rank and SIGKILL about a second later: the image is then written only
if the current pass ends in that time. To stop a long pass, send mpirun SIGUSR1.
Outputs are checked before rendering and written to new temporary files beside them, renamed
into place only when all were written, after every rank has ended its work: a rank that dies
makes mpirun end the run, and no image is written.
Exit status (rank 0's, which mpirun returns unless it was signalled itself): 0 on success
(--time-limit included), 1 for a bad scene, an unwritable output, a checkpoint that cannot be
resumed or written at the end (the images are written first), a CPU without an instruction set this build uses or a rank that failed, 2 for bad
options, 3 for a valid scene that this variant cannot render (a shading kind it was built
without), 128 + the signal's number when a signal stopped the render (138 for SIGUSR1).
)",
    Variant::info.name,
    cli::kVariantHasWavefront,
    cli::kProgramSimds,
    cli::kVariantWavefrontLanes};

// SIGUSR1 too: mpirun forwards it as it is, without killing the ranks a second later.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1};

struct MpiOptions {
  bool scene_everywhere = false;
  bool verbose = false;
};

// Point-to-point messages, all between rank 0 and one other rank.
enum Tag : int {
  kTagWork = 1,  ///< worker -> 0: finished tiles with their sums, and how many more it wants
  kTagAssign,    ///< 0 -> worker: tiles to render, with the sums of those it lacks
  kTagStop,      ///< 0 -> worker: the render is over
  kTagFailed,    ///< worker -> 0: what went wrong there
};

/// The longest a rank's main thread sleeps between two looks for messages while its threads
/// finish nothing: how late a request or an answer can be read. A look costs microseconds.
constexpr auto kPollInterval = std::chrono::microseconds(250);

/// How many tiles a rank with `threads` rendering threads and `queued` tiles not yet started asks
/// for: it keeps up to two per thread, and asks once one per thread or fewer are left, so that
/// every thread has a tile to go on with while the answer comes.
std::size_t tiles_wanted(std::size_t queued, int threads) {
  const auto per_thread = std::size_t(threads);
  return queued <= per_thread ? 2 * per_thread - queued : 0;
}

/// This process among the others: its rank, how many there are, and its host (for messages).
struct World {
  int rank = 0;
  int size = 1;
  std::string host;
};

[[noreturn]] void abort_run(const std::string& message) {
  std::cerr << message << std::flush;
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);  // MPI_Abort does not return
}

/// What a rank that failed sends rank 0: its host, a newline, and its message.
std::string failure_report(const World& world, std::string message) {
  if (message.empty() || message.back() != '\n') message += '\n';
  return world.host + "\n" + message;
}

/// Rank 0's words for another rank's failure_report.
std::string describe_failure(int rank, const std::string& report) {
  const std::size_t line = report.find('\n');
  return std::string(kProgram.name) + ": rank " + std::to_string(rank) + " (on " +
         report.substr(0, line) + ") failed:\n" + report.substr(line + 1);
}

// --- Messages ---------------------------------------------------------------------------

/// Fields appended to a message, in this machine's byte order (all ranks run the same build).
class Packer {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* from = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), from, from + sizeof value);
  }
  void put_sums(const glint::Tile& tile, const glint::PixelSums& sums) {
    for (int y = tile.y0; y < tile.y1; ++y) {
      const auto* row = reinterpret_cast<const char*>(&sums.at(tile.x0, y));
      bytes_.insert(bytes_.end(), row, row + std::size_t(tile.width()) * sizeof(glint::ColorSum));
    }
  }
  std::vector<char> take() { return std::move(bytes_); }

 private:
  std::vector<char> bytes_;
};

/// Reads a message's fields back; a message shorter than its fields is a protocol error.
class Unpacker {
 public:
  explicit Unpacker(const std::vector<char>& bytes)
      : at_(bytes.data()), end_(bytes.data() + bytes.size()) {}
  template <typename T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  void get_sums(const glint::Tile& tile, glint::PixelSums& sums) {
    const std::size_t row = std::size_t(tile.width()) * sizeof(glint::ColorSum);
    for (int y = tile.y0; y < tile.y1; ++y)
      std::memcpy(&sums.at(tile.x0, y), take(row), row);
  }
  bool done() const { return at_ == end_; }

 private:
  const char* take(std::size_t size) {
    if (std::size_t(end_ - at_) < size) throw std::runtime_error("a truncated message");
    const char* from = at_;
    at_ += size;
    return from;
  }
  const char* at_;
  const char* end_;
};

struct Message {
  int source = 0;
  int tag = 0;
  std::vector<char> bytes;
};

/// The next message that has arrived, if any.
std::optional<Message> poll() {
  int arrived = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return std::nullopt;
  int size = 0;
  MPI_Get_count(&status, MPI_BYTE, &size);
  Message message{status.MPI_SOURCE, status.MPI_TAG, std::vector<char>(std::size_t(size))};
  MPI_Recv(message.bytes.data(), size, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return message;
}

/// Messages being sent, kept until MPI is done with them. Never a blocking send: two ranks
/// sending each other large messages at once would both wait for the other to receive.
class Outbox {
 public:
  void send(int to, Tag tag, std::vector<char> bytes) {
    bytes_ += bytes.size();
    ++messages_;
    pending_.push_back({MPI_REQUEST_NULL, std::move(bytes)});
    Pending& p = pending_.back();
    MPI_Isend(p.bytes.data(), int(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD, &p.request);
  }
  /// Lets MPI move the messages on, and forgets those sent.
  void progress() {
    std::erase_if(pending_, [](Pending& p) {
      int done = 0;
      MPI_Test(&p.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }
  void flush() {
    for (Pending& p : pending_)
      MPI_Wait(&p.request, MPI_STATUS_IGNORE);
    pending_.clear();
  }
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t messages() const { return messages_; }

 private:
  // A vector's buffer stays where it is when the vector is moved: MPI keeps its address.
  struct Pending {
    MPI_Request request;
    std::vector<char> bytes;
  };
  std::vector<Pending> pending_;
  std::uint64_t bytes_ = 0;
  std::uint64_t messages_ = 0;
};

// --- Agreeing on failures before the render ---------------------------------------------

/// Every rank says whether its step failed; when one did, rank 0 prints one message (its own,
/// or else the first failing rank's) and every rank gets the status to exit with (0: go on).
/// So a scene error that every rank meets is printed once.
int agree(const World& world, const std::optional<cli::Failure>& mine) {
  const int status = mine ? mine->status : 0;
  std::vector<int> statuses(std::size_t(world.size));
  MPI_Gather(&status, 1, MPI_INT, statuses.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int chosen[2] = {-1, 0};  // the rank whose message is printed, and the status
  if (world.rank == 0)
    for (int r = 0; r < world.size; ++r)
      if (statuses[std::size_t(r)] != 0) {
        chosen[0] = r;
        chosen[1] = statuses[std::size_t(r)];
        break;
      }
  MPI_Bcast(chosen, 2, MPI_INT, 0, MPI_COMM_WORLD);
  if (chosen[0] < 0) return 0;
  if (chosen[0] == world.rank && world.rank == 0) {
    std::cerr << mine->message;
  } else if (chosen[0] == world.rank) {
    const std::string text = failure_report(world, mine->message);
    MPI_Send(text.data(), int(text.size()), MPI_CHAR, 0, kTagFailed, MPI_COMM_WORLD);
  } else if (world.rank == 0) {
    MPI_Status probe;
    MPI_Probe(chosen[0], kTagFailed, MPI_COMM_WORLD, &probe);
    int size = 0;
    MPI_Get_count(&probe, MPI_CHAR, &size);
    std::string text(std::size_t(size), '\0');
    MPI_Recv(text.data(), size, MPI_CHAR, chosen[0], kTagFailed, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::cerr << describe_failure(chosen[0], text);
  }
  return chosen[1];
}

/// Throws unless this rank renders the image rank 0 renders: the same variant and execution
/// model and every setting that changes the image (the thread count does not), naming the
/// first difference. Every rank's work goes into one image, so ranks started with different
/// options (mpirun's A : B form) would otherwise mix two renders into one. The scene's bytes
/// are agreed on elsewhere (rank 0 sends them, or --scene-everywhere compares their hashes).
void check_same_image(const cli::Options& options, const glint::RenderSettings& settings) {
  const bool scalar = cli::execution_model(kProgram, options) == cli::ExecutionModel::scalar;
  const std::string renderer =
      std::string(kProgram.variant) + (scalar ? ", scalar" : ", wavefront");
  std::uint64_t size = renderer.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  std::string rank0_renderer = renderer;  // rank 0's own, elsewhere overwritten
  rank0_renderer.resize(std::size_t(size));
  MPI_Bcast(rank0_renderer.data(), int(size), MPI_CHAR, 0, MPI_COMM_WORLD);

  struct Field {
    const char* name;
    std::uint64_t value;
  };
  const Field mine[] = {
      {"width", std::uint64_t(settings.width)},
      {"height", std::uint64_t(settings.height)},
      {"samples per pixel", std::uint64_t(settings.samples_per_pixel)},
      {"max depth", std::uint64_t(settings.max_depth)},
      {"samples per pass at most", std::uint64_t(settings.max_pass_samples)},
      {"seed", settings.seed},
      {"antialias sigma bits", std::bit_cast<std::uint32_t>(settings.antialias_sigma)}};
  constexpr std::size_t kFields = std::size(mine);
  std::uint64_t rank0[kFields];
  for (std::size_t i = 0; i < kFields; ++i)
    rank0[i] = mine[i].value;
  MPI_Bcast(rank0, int(kFields), MPI_UINT64_T, 0, MPI_COMM_WORLD);

  const std::string advice =
      ": every rank must be started with the same image options (--seed, --max-depth, --spp, "
      "--width, --height, --scalar) and the same program";
  if (rank0_renderer != renderer)
    throw glint::Error("this rank renders with " + renderer + ", rank 0 with " + rank0_renderer +
                       advice);
  for (std::size_t i = 0; i < kFields; ++i)
    if (rank0[i] != mine[i].value)
      throw glint::Error(std::string("this rank has ") + mine[i].name + " " +
                         std::to_string(mine[i].value) + ", rank 0 has " +
                         std::to_string(rank0[i]) + advice);
}

/// Runs a step on this rank, catching its failure for agree().
template <typename Step>
std::optional<cli::Failure> attempt(const Step& step) {
  try {
    step();
    return std::nullopt;
  } catch (...) {
    return cli::current_failure(kProgram);
  }
}

/// The CPUs this process may run on: mpirun binds each rank to a core by default.
int cpus_available() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, int(std::thread::hardware_concurrency()));
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The CPU time the calling thread has used (Linux), in seconds.
double thread_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// How long the scene took to reach every rank, as rank 0 saw it, in seconds from the start.
struct LoadTimes {
  std::uint64_t bytes = 0;
  double read = 0.0;   ///< rank 0 had read the file
  double sent = 0.0;   ///< every rank had the text (broadcast, or each read it)
  double built = 0.0;  ///< rank 0 had parsed and built the scene
  double ready = 0.0;  ///< every rank had
};

/// The text of the scene on every rank: read by rank 0 and broadcast, or read by each.
/// Throws SceneError on the ranks that cannot read it, and on the others when rank 0 cannot.
std::string scene_text(const World& world, const cli::Options& options, const MpiOptions& mpi,
                       cli::LoadProgress& loading, Clock::time_point start, LoadTimes& times) {
  if (mpi.scene_everywhere) {
    std::string text = cli::scene_file_text(loading, options.scene);
    times.read = seconds_since(start);
    return text;
  }
  std::string text;
  std::uint64_t size = UINT64_MAX;  // rank 0 could not read it
  std::exception_ptr failure;
  if (world.rank == 0) try {
      text = cli::scene_file_text(loading, options.scene);
      size = text.size();
      times.read = seconds_since(start);
    } catch (...) {
      failure = std::current_exception();
    }
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (failure) std::rethrow_exception(failure);
  if (size == UINT64_MAX)
    throw glint::SceneError(options.scene, 0, "rank 0 could not read the scene");
  text.resize(std::size_t(size));
  // At most kMaxSceneFileSize (1 GiB): one count of bytes.
  MPI_Bcast(text.data(), int(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

// --- The render ---------------------------------------------------------------------------

/// One rank's rendering threads, running the execution model's render_tiles on a thread of their
/// own, fed by a TileQueue.
class RankRenderer {
 public:
  RankRenderer(const glint::Scene& scene, const glint::RenderSettings& settings,
               glint::PixelSums& sums, cli::ExecutionModel model)
      : start_(Clock::now()),
        main_cpu_start_(thread_cpu_seconds()),
        thread_([this, &scene, &settings, &sums, model] {
          try {
            stats_ = cli::with_renderer<Variant>(model, [&]<typename Renderer>() {
              return Renderer::render_tiles(scene, settings, sums, queue_);
            });
          } catch (...) {
            failure_ = cli::current_failure(kProgram);
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
  std::optional<cli::Failure> started() {
    while (!queue_.threads_started() && !ended_.load())
      queue_.wait(std::chrono::milliseconds(1));
    return failed();
  }
  /// What went wrong, once the rendering has ended by an error.
  std::optional<cli::Failure> failed() const { return ended_.load() ? failure_ : std::nullopt; }
  /// Ends the rendering once the queue is empty, and waits for it.
  void finish() {
    queue_.close();
    thread_.join();
    window_ = std::chrono::duration<double>(Clock::now() - start_).count();
  }
  cli::TileQueue& queue() { return queue_; }
  const glint::RenderStats& stats() const { return stats_; }
  /// Since the threads started, until finish().
  double window_seconds() const { return window_; }
  /// The CPU time of the calling (main) thread since the threads started.
  double main_cpu_seconds() const { return thread_cpu_seconds() - main_cpu_start_; }

 private:
  cli::TileQueue queue_;
  glint::RenderStats stats_;
  std::optional<cli::Failure> failure_;
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

std::vector<RankReport> gather_reports(const World& world, RankRenderer& renderer,
                                       std::uint64_t tiles) {
  const glint::RenderStats& stats = renderer.stats();
  const RankReport mine{renderer.queue().waited_seconds() / std::max(1, stats.threads),
                        renderer.window_seconds(),
                        stats.rays,
                        stats.invalid_samples,
                        tiles,
                        renderer.main_cpu_seconds(),
                        stats.threads};
  std::vector<RankReport> all(std::size_t(world.size));
  MPI_Gather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
  return all;
}

/// The samples of a pass: [first, last).
struct PassSamples {
  int first, last;
};

/// A rank other than 0: renders what rank 0 assigns until told to stop.
void serve(const World& world, const glint::RenderSettings& settings, RankRenderer& renderer,
           glint::PixelSums& sums, int threads) {
  const glint::TileGrid grid(settings);
  cli::TileQueue& queue = renderer.queue();
  Outbox outbox;
  bool asked = false;  // a request is waiting for rank 0's answer
  std::uint64_t tiles = 0;
  const auto fail = [&](const std::string& message) {
    // Rank 0 prints it and ends the run; this rank waits for that, or does it itself.
    const std::string text = failure_report(world, message);
    MPI_Send(text.data(), int(text.size()), MPI_CHAR, 0, kTagFailed, MPI_COMM_WORLD);
    std::this_thread::sleep_for(std::chrono::seconds(10));
    abort_run(describe_failure(world.rank, text));
  };
  try {
    for (bool stop = false; !stop;) {
      outbox.progress();
      while (std::optional<Message> message = poll()) {
        if (message->tag == kTagStop) {
          stop = true;
          break;
        }
        if (message->tag != kTagAssign) throw std::runtime_error("an unexpected message");
        Unpacker in(message->bytes);
        const auto samples = in.get<PassSamples>();
        const auto count = in.get<std::uint32_t>();
        for (std::uint32_t i = 0; i < count; ++i) {
          const auto tile = in.get<std::uint32_t>();
          const auto with_sums = in.get<std::uint8_t>();
          if (tile >= grid.count) throw std::runtime_error("a tile out of range");
          if (with_sums) in.get_sums(grid.tile(tile), sums);
          queue.add({tile, samples.first, samples.last, 0});
        }
        if (!in.done()) throw std::runtime_error("a message longer than its fields");
        asked = false;
      }
      if (stop) break;
      if (const std::optional<cli::Failure> failure = renderer.failed()) fail(failure->message);
      const std::vector<glint::TileWork> done = queue.take_finished();
      const std::size_t queued = queue.queued();
      const auto want = std::uint32_t(asked ? 0 : tiles_wanted(queued, threads));
      if (!done.empty() || want > 0) {
        Packer out;
        out.put(want);
        out.put(std::uint32_t(done.size()));
        for (const glint::TileWork& work : done) {
          out.put(std::uint32_t(work.tile));
          out.put(PassSamples{work.first_sample, work.last_sample});
          out.put_sums(grid.tile(work.tile), sums);
        }
        outbox.send(0, kTagWork, out.take());
        asked = asked || want > 0;
        tiles += done.size();
      }
      queue.wait(kPollInterval);
    }
  } catch (const std::exception& error) {
    fail(std::string("error: ") + error.what());
  }
  outbox.flush();
  renderer.finish();
  if (const std::optional<cli::Failure> failure = renderer.failed()) fail(failure->message);
  gather_reports(world, renderer, tiles);
}

/// Bytes and messages of one pass, as rank 0 sees them (every message goes to or from it).
struct PassTraffic {
  double seconds = 0.0;
  std::uint64_t bytes_in = 0, messages_in = 0;    ///< requests and finished tiles' sums
  std::uint64_t bytes_out = 0, messages_out = 0;  ///< assignments and moved tiles' sums
  std::uint64_t sums_back = 0, sums_moved = 0;    ///< of which sums, bytes
  std::uint64_t tiles_moved = 0;
};

std::string megabytes(std::uint64_t bytes) {
  char text[32];
  if (bytes < 1000000)
    std::snprintf(text, sizeof text, "%.1f kB", double(bytes) * 1e-3);
  else
    std::snprintf(text, sizeof text, "%.2f MB", double(bytes) * 1e-6);
  return text;
}

/// Rank 0: schedules the passes, renders with its own threads, gathers the sums, reports.
class Coordinator {
 public:
  Coordinator(const World& world, const glint::RenderSettings& settings, glint::PixelSums& sums,
              RankRenderer& renderer, int threads, bool resumed)
      : world_(world),
        settings_(settings),
        sums_(sums),
        renderer_(renderer),
        threads_(threads),
        grid_(settings),
        ends_(glint::pass_ends(settings.samples_per_pixel, settings.max_pass_samples)),
        scheduler_(grid_.count, world.size, !resumed),
        asked_(std::size_t(world.size), 0) {}

  /// Renders the passes from `first_pass` on, under `control`, as Renderer::render does.
  glint::RenderResult render(const glint::RenderControl& control, int first_pass) {
    const auto start = Clock::now();
    const auto elapsed = [&] {
      return std::chrono::duration<double>(Clock::now() - start).count();
    };
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
    for (pass_ = first_pass_; pass_ < ends_.size(); ++pass_) {
      if (control.stop && control.stop->load(std::memory_order_relaxed)) break;
      const double pass_start = elapsed();
      traffic_.emplace_back();
      counting_ = &traffic_.back();
      scheduler_.begin_pass();
      for (int r = 1; r < world_.size; ++r)
        if (asked_[std::size_t(r)] > 0) hand_out(r, std::exchange(asked_[std::size_t(r)], 0));
      while (!scheduler_.pass_complete()) {
        step();
        if (elapsed() - last_report >= 0.1) report(false);
        if (!scheduler_.pass_complete()) renderer_.queue().wait(kPollInterval);
      }
      traffic_.back().seconds = elapsed() - pass_start;
      traffic_.back().tiles_moved = scheduler_.moved();
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
    if (const std::optional<cli::Failure> failure = renderer_.failed()) abort_run(failure->message);
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

  /// "3 ranks x 2 threads", or "3 ranks, 5 threads (2+2+1)" when they differ.
  std::string workers() const {
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

  /// The lines after the summary: idle time per rank and bytes sent; with `verbose`, a line
  /// per pass and per rank.
  std::string report_lines(bool verbose) const {
    PassTraffic total = between_passes_;
    for (const PassTraffic& t : traffic_) {
      total.bytes_in += t.bytes_in;
      total.messages_in += t.messages_in;
      total.bytes_out += t.bytes_out;
      total.messages_out += t.messages_out;
      total.sums_back += t.sums_back;
      total.sums_moved += t.sums_moved;
      total.tiles_moved += t.tiles_moved;
    }
    const std::string name = kProgram.name;
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
            std::to_string(total.tiles_moved) + " tiles)\n";
    if (!verbose) return text;
    for (std::size_t p = 0; p < traffic_.size(); ++p) {
      const PassTraffic& t = traffic_[p];
      std::snprintf(line, sizeof line,
                    "%s: pass %zu (%d spp): %.3f s; to rank 0 %s in %llu messages, from rank 0 %s "
                    "in %llu messages; %llu tiles moved (%s of sums)\n",
                    name.c_str(), first_pass_ + p + 1, ends_[first_pass_ + p], t.seconds,
                    megabytes(t.bytes_in).c_str(), static_cast<unsigned long long>(t.messages_in),
                    megabytes(t.bytes_out).c_str(), static_cast<unsigned long long>(t.messages_out),
                    static_cast<unsigned long long>(t.tiles_moved),
                    megabytes(t.sums_moved).c_str());
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

 private:
  /// One round: the messages that came, the tiles rank 0's threads finished, more for them.
  void step() {
    outbox_.progress();
    while (std::optional<Message> message = poll())
      receive(*message);
    if (const std::optional<cli::Failure> failure = renderer_.failed()) abort_run(failure->message);
    cli::TileQueue& queue = renderer_.queue();
    for (const glint::TileWork& work : queue.take_finished()) {
      scheduler_.finished();
      samples_done_ +=
          grid_.tile(work.tile).pixel_count() * std::uint64_t(work.last_sample - work.first_sample);
      ++local_tiles_;
    }
    if (const std::size_t want = tiles_wanted(queue.queued(), threads_); want > 0)
      for (const cli::TileScheduler::Assignment& a : scheduler_.assign(0, want))
        queue.add({a.tile, samples().first, samples().last, 0});
  }

  PassSamples samples() const { return {pass_ == 0 ? 0 : ends_[pass_ - 1], ends_[pass_]}; }

  void receive(const Message& message) {
    if (message.tag == kTagFailed)
      abort_run(describe_failure(message.source,
                                 std::string(message.bytes.begin(), message.bytes.end())));
    const auto protocol_error = [&](const char* what) {
      abort_run(std::string(kProgram.name) + ": error: rank " + std::to_string(message.source) +
                " sent " + what + "\n");
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

  /// Tiles for a rank that asked for `want`, or its request held until the next pass.
  void hand_out(int rank, std::uint32_t want) {
    // Between passes every queue is empty: the request waits for the next pass.
    const std::vector<cli::TileScheduler::Assignment> given = scheduler_.assign(rank, want);
    if (given.empty()) {
      asked_[std::size_t(rank)] = want;
      return;
    }
    Packer out;
    out.put(samples());
    out.put(std::uint32_t(given.size()));
    PassTraffic& traffic = *counting_;
    for (const cli::TileScheduler::Assignment& a : given) {
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

  /// Tells every other rank that the render is over, once each has asked for more: then no
  /// message of theirs is left unreceived.
  void stop_workers() {
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

  const World& world_;
  const glint::RenderSettings& settings_;
  glint::PixelSums& sums_;
  RankRenderer& renderer_;
  const int threads_;
  const glint::TileGrid grid_;
  const std::vector<int> ends_;
  cli::TileScheduler scheduler_;
  std::vector<std::uint32_t> asked_;  ///< per rank: tiles asked for, held until the next pass
  std::size_t first_pass_ = 0;
  std::size_t pass_ = 0;  ///< the pass being rendered, or the last one
  std::uint64_t samples_done_ = 0;
  std::uint64_t local_tiles_ = 0;
  Outbox outbox_;
  std::vector<PassTraffic> traffic_;  ///< per pass rendered
  PassTraffic between_passes_;        ///< requests that came between passes
  PassTraffic* counting_ = &between_passes_;
  std::vector<RankReport> reports_;
};

/// --verbose's line on the scene's way to the ranks.
std::string load_line(const LoadTimes& t, const MpiOptions& mpi) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%s: scene: %s, read by rank 0 after %.3f s, on every rank (%s) after %.3f s; "
                "parsed and built by rank 0 after %.3f s, by every rank after %.3f s\n",
                kProgram.name, megabytes(t.bytes).c_str(), t.read,
                mpi.scene_everywhere ? "each read it" : "broadcast", t.sent, t.built, t.ready);
  return line;
}

#if defined(GLINT_RENDER_SIMD_SETS)
}  // namespace
// Each defined by this file compiled for its instruction set (GLINT_ISA_LEVEL): run() there, for
// a rank of MPI_COMM_WORLD already initialised.
extern "C" int glint_render_mpi_sse2(int rank, int size, const char* host, int argc, char** argv);
extern "C" int glint_render_mpi_avx2(int rank, int size, const char* host, int argc, char** argv);
extern "C" int glint_render_mpi_avx512(int rank, int size, const char* host, int argc, char** argv);
namespace {
#endif

int run(const World& world, int argc, char** argv) {
  cli::Options options;
  MpiOptions mpi;
  const auto own_option = [&](std::string_view arg, const std::function<std::string_view()>&) {
    if (arg == "--scene-everywhere") return mpi.scene_everywhere = true;
    if (arg == "--verbose") return mpi.verbose = true;
    return false;
  };
  // Every rank parses the same arguments; rank 0 alone speaks.
  glint::Simd simd;
  try {
    options = cli::parse_options(argc, argv, kProgram, own_option);
    simd = cli::run_simd(kProgram, options);
  } catch (const cli::UsageError&) {
    const cli::Failure failure = cli::current_failure(kProgram);
    if (world.rank == 0) std::cerr << failure.message;
    return failure.status;
  }
  if (options.help) {
    if (world.rank == 0) std::cout << cli::help_text(kProgram);
    return 0;
  }
  // Each rank runs the renderer of the instruction set it chose: all give the same image.
  if (simd != glint::kCompiledSimd) {
#if defined(GLINT_RENDER_SIMD_SETS)
    const char* host = world.host.c_str();
    switch (simd) {
      case glint::Simd::scalar:
        return glint_render_mpi_sse2(world.rank, world.size, host, argc, argv);
      case glint::Simd::avx2:
        return glint_render_mpi_avx2(world.rank, world.size, host, argc, argv);
      case glint::Simd::avx512:
        return glint_render_mpi_avx512(world.rank, world.size, host, argc, argv);
    }
#endif
    if (world.rank == 0)
      std::cerr << kProgram.name << ": error: no renderer for --simd " << glint::simd_name(simd)
                << " in this program\n";
    return 1;
  }
  // Once MPI is initialised, so that these handlers, not MPI's, answer the stop signals; by the
  // instruction set that renders, whose stop flag they set.
  cli::install_signal_handlers(kProgram.name, kStopSignals);
  const bool speak = world.rank == 0 && !options.quiet;

  std::string output;
  if (int status = agree(world, attempt([&] {
                           if (world.rank == 0) output = cli::check_outputs(options);
                         })))
    return status;

  std::optional<glint::Scene> scene;
  glint::RenderSettings settings;
  std::uint64_t scene_hash = 0;  // of the file's bytes, for checkpoints and --scene-everywhere
  LoadTimes times;
  {
    const Clock::time_point start = Clock::now();
    cli::LoadProgress loading(speak, options.scene);
    std::string text;
    if (int status = agree(
            world, attempt([&] { text = scene_text(world, options, mpi, loading, start, times); })))
      return status;
    times.sent = seconds_since(start);
    times.bytes = text.size();
    if (mpi.scene_everywhere || (world.rank == 0 && (options.checkpoint || options.resume)))
      scene_hash = cli::scene_text_hash(text);
    std::uint64_t rank0_hash = scene_hash;
    if (mpi.scene_everywhere) MPI_Bcast(&rank0_hash, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    if (int status =
            agree(world, attempt([&] {
                    if (rank0_hash != scene_hash)
                      throw glint::Error("cannot render " + options.scene +
                                         ": its bytes here differ from rank 0's");
                    scene.emplace(cli::parse_and_build(loading, std::move(text), options.scene));
                    times.built = seconds_since(start);
                    glint::check_supported<Variant>(*scene);
                    settings = cli::render_settings(options, *scene);
                    if (!options.threads)
                      settings.threads = std::min(cpus_available(), glint::limits::max_threads);
                  })))
      return status;
    times.ready = seconds_since(start);
  }
  if (int status = agree(world, attempt([&] { check_same_image(options, settings); })))
    return status;
  const glint::TileGrid grid(settings);
  const int threads = int(std::min<std::size_t>(std::size_t(settings.threads), grid.count));

  std::optional<cli::PassKeeper> keeper;
  glint::PixelSums sums(settings.width, settings.height);
  std::optional<RankRenderer> renderer;
  if (int status = agree(world, attempt([&] {
                           if (world.rank == 0) {
                             keeper.emplace(kProgram, options, settings, scene_hash);
                             if (const glint::RenderStart start = keeper->start(); start.sums)
                               sums = *start.sums;
                           }
                           renderer.emplace(*scene, settings, sums,
                                            cli::execution_model(kProgram, options));
                           if (std::optional<cli::Failure> failure = renderer->started())
                             throw glint::Error(failure->message);
                         })))
    return status;

  if (world.rank != 0) {
    serve(world, settings, *renderer, sums, threads);
    return 0;
  }
  // From here on, an error on rank 0 ends every rank (abort_run).
  try {
    const glint::RenderStart start = keeper->start();
    Coordinator coordinator(world, settings, sums, *renderer, threads, start.sums != nullptr);
    const glint::RenderControl control{cli::ProgressPrinter(!options.quiet), keeper->callback(),
                                       &cli::stop_requested};
    glint::RenderResult result = coordinator.render(control, start.passes_done);
    renderer.reset();
    // The sums of the last completed pass (the render stops between passes), for the checkpoint.
    if (options.checkpoint) result.sums = std::move(sums);
    std::string lines = coordinator.report_lines(mpi.verbose);
    if (mpi.verbose) lines += load_line(times, mpi);
    return cli::finish_run(kProgram, options, output, settings, std::move(result), *keeper,
                           {coordinator.workers(), lines});
  } catch (const glint::ImageWriteError&) {
    // The render is over and every rank has ended its work: only rank 0 fails.
    const cli::Failure failure = cli::current_failure(kProgram);
    std::cerr << failure.message;
    return failure.status;
  } catch (...) {
    abort_run(cli::current_failure(kProgram).message);
  }
}

}  // namespace

#if defined(GLINT_RENDER_SIMD_SETS)
extern "C" int GLINT_ISA_CONCAT(glint_render_mpi_, GLINT_ISA_LEVEL)(int rank, int size,
                                                                    const char* host, int argc,
                                                                    char** argv) {
  return run(World{rank, size, host}, argc, argv);
}
#endif

#if !defined(GLINT_RENDER_SIMD_SETS) || defined(GLINT_RENDER_MAIN)
int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  World world;
  MPI_Comm_rank(MPI_COMM_WORLD, &world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world.size);
  char host[MPI_MAX_PROCESSOR_NAME];
  int host_size = 0;
  MPI_Get_processor_name(host, &host_size);
  world.host.assign(host, std::size_t(host_size));
  const int status = run(world, argc, argv);
  MPI_Finalize();
  return status;
}
#endif
