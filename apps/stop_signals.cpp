// stop_signals.hpp's definitions: the handler and what it shares with the program.

#include "stop_signals.hpp"

#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

// What the handler shares with the program: only lock-free atomics and fixed buffers, written
// with the signals blocked, so that the handler reads them whole.

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free &&
              std::atomic<std::int64_t>::is_always_lock_free);
std::atomic<bool> stop_requested{false};

namespace {

std::atomic<int> stop_signal{0};  ///< the first stop signal received, or 0
/// When the first stop signal came (CLOCK_MONOTONIC, nanoseconds); 0 until its handler has
/// noted it.
std::atomic<std::int64_t> first_stop_time{0};
/// The same signal again within this time of the first is the same stop, not a second one:
/// `timeout`, systemd and job schedulers signal the process and then its process group, so
/// the process gets two copies at once.
constexpr std::int64_t kRepeatedSignalWindow = 1'000'000'000;
constexpr int kMaxTemporaries = 5;  // the PNG, the PFM, the EXR, the stats and the checkpoint
char temporaries[kMaxTemporaries][PATH_MAX];
std::atomic<int> temporary_count{0};
constexpr int kMaxStopSignals = 8;
int stop_signals[kMaxStopSignals];
int stop_signal_count = 0;
char second_signal_message[128];
std::size_t second_signal_message_size = 0;

}  // namespace

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    case SIGUSR1:
      return "SIGUSR1";
    case SIGALRM:
      return "SIGALRM";
    case SIGXCPU:
      return "SIGXCPU";
    default:
      return "a signal";
  }
}

BlockStopSignals::BlockStopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int i = 0; i < stop_signal_count; ++i)
    sigaddset(&signals, stop_signals[i]);
  pthread_sigmask(SIG_BLOCK, &signals, &previous_);
}

BlockStopSignals::~BlockStopSignals() {
  pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
}

bool note_temporary(const std::string& path) {
  const int count = temporary_count.load();
  if (path.size() >= PATH_MAX || count >= kMaxTemporaries) return false;
  std::memcpy(temporaries[count], path.c_str(), path.size() + 1);
  temporary_count.store(count + 1);
  return true;
}

void forget_temporaries() {
  const BlockStopSignals block;
  temporary_count.store(0);
}

int received_stop_signal() {
  return stop_signal.load();
}

// Internal linkage: glint-render links this file once per instruction set.
extern "C" {
static void on_stop_signal(int signal) {
  // Async-signal-safe only: atomics, clock_gettime, unlink, write and _exit.
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  const std::int64_t time = std::int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
  int first = 0;
  if (stop_signal.compare_exchange_strong(first, signal)) {
    first_stop_time.store(std::max<std::int64_t>(time, 1));
    stop_requested.store(true);
    return;
  }
  // The same signal while the first one's handler is still noting its time, or soon after it:
  // another copy of the same stop. SIGXCPU is always the same stop: past a soft CPU limit the
  // kernel sends it again every second of CPU time.
  const std::int64_t first_time = first_stop_time.load();
  if (first == signal &&
      (signal == SIGXCPU || first_time == 0 || time - first_time < kRepeatedSignalWindow))
    return;
  for (int i = 0, n = temporary_count.load(); i < n; ++i)
    unlink(temporaries[i]);
  [[maybe_unused]] const ssize_t written =
      write(STDERR_FILENO, second_signal_message, second_signal_message_size);
  _exit(128 + signal);
}
}

void install_signal_handlers(const char* program, std::span<const int> signals) {
  std::snprintf(second_signal_message, sizeof second_signal_message,
                "\n%s: a second stop signal: exiting at once\n", program);
  second_signal_message_size = std::strlen(second_signal_message);
  stop_signal_count = 0;
  for (const int signal : signals.first(std::min<std::size_t>(signals.size(), kMaxStopSignals)))
    stop_signals[stop_signal_count++] = signal;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < stop_signal_count; ++i) {
    // A signal ignored on entry stays ignored: nohup and background jobs rely on it.
    struct sigaction previous {};
    if (sigaction(stop_signals[i], nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
      continue;
    sigaction(stop_signals[i], &action, nullptr);
  }
  // Past `ulimit -f`, write() then fails with EFBIG and the temporary is removed; by default
  // the signal would kill the process and leave the temporary behind.
  std::signal(SIGXFSZ, SIG_IGN);
  // A reader of stderr that goes away (`| head`) must not end the render: the write fails with
  // EPIPE instead, and the progress stops (progress_printer.hpp).
  std::signal(SIGPIPE, SIG_IGN);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
