#pragma once
// The peak memory of running a function in a child process: how tests show that a reader
// refuses a file before allocating what its header claims. A forked child starts with its
// parent's pages, so what counts is how far its peak exceeds that of a child doing nothing.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace glint_test {

/// How a child ended: its exit status (-1 if killed, e.g. by the alarm) and its peak resident
/// memory in kilobytes.
struct ChildRun {
  int status = -1;
  long peak_kb = 0;
};

/// Runs `work` (returning the child's exit status) in a forked child, killed after
/// `seconds` so that a read that never ends fails the test instead of hanging it.
template <typename Work>
ChildRun run_in_child(Work work, unsigned seconds = 60) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    alarm(seconds);
    int status = 1;
    try {
      status = work();
    } catch (...) {
      status = 2;
    }
    _exit(status);
  }
  ChildRun run;
  if (pid < 0) return run;
  int wait_status = 0;
  struct rusage usage {};
  if (wait4(pid, &wait_status, 0, &usage) != pid) return run;
  run.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  run.peak_kb = usage.ru_maxrss;
  return run;
}

/// Runs `work` in a child as run_in_child, with the peak memory given as the kilobytes above
/// those of a child that does nothing.
template <typename Work>
ChildRun run_in_child_above_baseline(Work work, unsigned seconds = 60) {
  const ChildRun idle = run_in_child([] { return 0; });
  ChildRun run = run_in_child(work, seconds);
  run.peak_kb -= idle.peak_kb;
  return run;
}

}  // namespace glint_test
